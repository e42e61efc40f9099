// Draws a module's README.md handout with ImGui: headings, wrapped paragraphs, lists, code
// blocks and tables (the subset of Markdown the handouts use).
#pragma once

#include <string>

namespace pbrlab {

void drawHandout(const std::string& markdown);

}  // namespace pbrlab
