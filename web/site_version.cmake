# The site's version in its page (web/CMakeLists.txt, run after the page and its grader are
# built): a digest of the programs and the data. The page keeps the grades' reports under it,
# so a site built anew grades its students' files anew (shell.html, pbrlabSiteVersion).
#   cmake -DSITE=DIR -P web/site_version.cmake
set(digests "")
foreach(file IN ITEMS index.wasm grader.wasm lab.data)
  file(SHA256 "${SITE}/${file}" digest)
  string(APPEND digests "${digest}")
endforeach()
string(SHA256 version "${digests}")
string(SUBSTRING "${version}" 0 16 version)
file(READ "${SITE}/index.html" page)
string(REGEX REPLACE "var pbrlabSiteVersion = '[^']*';" "var pbrlabSiteVersion = '${version}';"
       page "${page}")
file(WRITE "${SITE}/index.html" "${page}")
