#include "handout.h"

#include <imgui.h>

#include <sstream>
#include <vector>

namespace pbrlab {

namespace {

std::vector<std::string> splitCells(const std::string& row) {
    std::vector<std::string> cells;
    std::string cell;
    for (size_t i = 1; i < row.size(); ++i) {
        if (row[i] == '|') {
            size_t b = cell.find_first_not_of(' '), e = cell.find_last_not_of(' ');
            cells.push_back(b == std::string::npos ? "" : cell.substr(b, e - b + 1));
            cell.clear();
        } else {
            cell += row[i];
        }
    }
    return cells;
}

std::string stripInline(std::string s) {
    // Drop emphasis and code backticks: ImGui text has one font.
    std::string out;
    for (char c : s)
        if (c != '`' && c != '*') out += c;
    return out;
}

void flushTable(std::vector<std::vector<std::string>>& rows, int& tableId) {
    if (rows.empty()) return;
    size_t columns = rows[0].size();
    if (ImGui::BeginTable(
            ("table" + std::to_string(tableId++)).c_str(), int(columns),
            ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
        for (size_t r = 0; r < rows.size(); ++r) {
            if (r == 1) continue;  // the |---| separator
            ImGui::TableNextRow();
            for (size_t c = 0; c < columns && c < rows[r].size(); ++c) {
                ImGui::TableSetColumnIndex(int(c));
                ImGui::TextWrapped("%s", stripInline(rows[r][c]).c_str());
            }
        }
        ImGui::EndTable();
    }
    rows.clear();
}

}  // namespace

void drawHandout(const std::string& markdown) {
    std::istringstream in(markdown);
    std::string line, paragraph;
    bool code = false;
    std::vector<std::vector<std::string>> table;
    int tableId = 0;
    const ImVec4 heading(1.0f, 0.8f, 0.45f, 1.0f), codeColor(0.6f, 0.85f, 1.0f, 1.0f);
    bool bullet = false;  // the paragraph is a list item (its lines continue it)
    auto flushParagraph = [&] {
        if (!paragraph.empty()) {
            if (bullet) ImGui::Bullet();
            ImGui::TextWrapped("%s", stripInline(paragraph).c_str());
        }
        paragraph.clear();
        bullet = false;
    };
    while (std::getline(in, line)) {
        if (line.rfind("```", 0) == 0) {
            flushParagraph();
            code = !code;
            continue;
        }
        bool indentedCode = line.rfind("    ", 0) == 0 && paragraph.empty();
        if (code || indentedCode) {
            ImGui::TextColored(codeColor, "  %s", line.c_str() + (indentedCode ? 4 : 0));
            continue;
        }
        if (line.rfind("|", 0) == 0) {
            flushParagraph();
            table.push_back(splitCells(line));
            continue;
        }
        flushTable(table, tableId);
        if (line.empty()) {
            flushParagraph();
            ImGui::Spacing();
        } else if (line[0] == '#') {
            flushParagraph();
            size_t level = line.find_first_not_of('#');
            ImGui::Spacing();
            ImGui::PushTextWrapPos(0);  // a long title wraps in a narrow window
            ImGui::TextColored(heading, "%s", stripInline(line.substr(level + 1)).c_str());
            ImGui::PopTextWrapPos();
            if (level == 1) ImGui::Separator();
        } else if (line.rfind("- ", 0) == 0 || line.rfind("* ", 0) == 0) {
            flushParagraph();
            bullet = true;
            paragraph = line.substr(2);
        } else {
            const size_t text = line.find_first_not_of(' ');  // continuation lines are indented
            if (text == std::string::npos) {                  // only spaces: a blank line
                flushParagraph();
                continue;
            }
            paragraph += (paragraph.empty() ? "" : " ") + line.substr(text);
        }
    }
    flushTable(table, tableId);
    flushParagraph();
}

}  // namespace pbrlab
