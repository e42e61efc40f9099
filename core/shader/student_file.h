// The one screening path for a student's files: every command that reads one (check, grade,
// gui, stability, mutants, the GUI's console and its hot reload) reads it through
// readStudentFile, directly or through the shader preprocessor, so a FIFO, a device, a huge
// file, a binary file or a link out of the submission folder is refused the same way
// everywhere, with the same words, and never blocks.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace pbrlab {

// Larger than any GLSL function a student writes by three orders of magnitude; what a grader
// holds in memory per file.
constexpr std::uintmax_t kMaxStudentFileBytes = 10u * 1024 * 1024;

// Empty when `file` may be read as a student's file of the submission `folder`, else why not
// ("refused: not a regular file (a FIFO)", "refused: larger than 10 MB", ...). Opens the file
// without blocking (a FIFO with no writer answers at once) and reads at most the limit.
std::string screenStudentFile(const std::filesystem::path& file,
                              const std::filesystem::path& folder);

// The file's text once screened; throws pbrlab::Error "<file>: <why>" otherwise. The checks
// are made on the open file itself, so a file swapped after screening is still refused.
std::string readStudentFile(const std::filesystem::path& file, const std::filesystem::path& folder);

}  // namespace pbrlab
