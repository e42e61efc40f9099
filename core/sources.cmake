# The source lists that the native build (core/CMakeLists.txt) and the browser build
# (web/CMakeLists.txt) share, relative to core/. Each build adds its own platform: core/native
# and host/desktop natively, core/web and host/web in a browser.

# The portable layers, in the order they may include each other: no OSMesa, OpenImageIO, child
# processes or resource limits (tests/layers/check_layers.cmake holds them to it).
set(pbrlab_portable_layers util assets steps gl shader ibl render grading)

# The student's GUI (host/gui), the same files on every platform; gui/platform.h is what it
# needs of the platform.
set(pbrlab_gui_sources
  host/gui/badges.cpp
  host/gui/console.cpp
  host/gui/evaluation_worker.cpp
  host/gui/frame.cpp
  host/gui/gui.cpp
  host/gui/handout.cpp
  host/gui/lab.cpp
  host/gui/panel_console.cpp
  host/gui/panel_module.cpp
  host/gui/panel_plot.cpp
  host/gui/panel_steps.cpp
  host/gui/panel_tabs.cpp
  host/gui/panel_view.cpp
  host/gui/redraw.cpp
  host/gui/source_watch.cpp
  host/gui/state.cpp
  host/gui/term_views.cpp
  host/gui/view_status.cpp
  host/gui/views.cpp)
