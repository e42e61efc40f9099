#include "shader/student_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "shader/preprocess.h"
#include "util/error.h"
#include "util/fs.h"

namespace fs = std::filesystem;

namespace pbrlab {

namespace {

const char* kindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a folder";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISSOCK(mode)) return "a socket";
    if (S_ISCHR(mode)) return "a character device";
    if (S_ISBLK(mode)) return "a block device";
    return "not a plain file";
}

// Closes the descriptor on every path out.
struct Descriptor {
    int fd = -1;
    ~Descriptor() {
        if (fd >= 0) ::close(fd);
    }
};

// The text, or why it is refused (then `text` is left empty).
std::string screenAndRead(const fs::path& file, const fs::path& folder, std::string* text) {
    std::error_code ec;
    if (fs::is_symlink(file, ec)) {
        const fs::path target = fs::canonical(file, ec);
        if (ec) return "refused: it is a link that cannot be resolved (" + ec.message() + ")";
        if (!isInside(target, folder))
            return "refused: it is a link to a file outside the submission folder";
    }
    if (!isInside(file, folder)) return "refused: outside the submission folder";
    // O_NONBLOCK: opening a FIFO for reading would otherwise wait for a writer forever.
    Descriptor d{::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY)};
    if (d.fd < 0)
        return errno == ENOENT ? "not found"
                               : std::string("cannot read it: ") + std::strerror(errno);
    struct stat st {};
    if (::fstat(d.fd, &st) != 0) return std::string("cannot read it: ") + std::strerror(errno);
    if (!S_ISREG(st.st_mode))
        return std::string("refused: not a regular file (") + kindOf(st.st_mode) + ")";
    if (std::uintmax_t(st.st_size) > kMaxStudentFileBytes)
        return "refused: larger than 10 MB (" + std::to_string(st.st_size / (1024 * 1024)) + " MB)";
    std::string bytes;
    bytes.resize(std::size_t(st.st_size));
    std::size_t got = 0;
    // A file that grows while it is read is read up to the size it had, plus one byte to
    // notice that it grew past the limit.
    char extra = 0;
    while (true) {
        const bool past = got >= bytes.size();
        const ssize_t n =
            past ? ::read(d.fd, &extra, 1) : ::read(d.fd, bytes.data() + got, bytes.size() - got);
        if (n < 0) {
            if (errno == EINTR) continue;
            return std::string("cannot read it: ") + std::strerror(errno);
        }
        if (n == 0) break;
        if (past) {
            if (bytes.size() + 1 > kMaxStudentFileBytes) return "refused: larger than 10 MB";
            bytes.push_back(extra);
        }
        got += std::size_t(n);
    }
    bytes.resize(got);
    // GL reads a shader as a C string: a NUL would silently cut the program short there.
    if (bytes.find('\0') != std::string::npos) return "refused: it contains NUL bytes (not text)";
    if (text) *text = std::move(bytes);
    return {};
}

}  // namespace

std::string screenStudentFile(const fs::path& file, const fs::path& folder) {
    return screenAndRead(file, folder, nullptr);
}

std::string readStudentFile(const fs::path& file, const fs::path& folder) {
    std::string text;
    if (std::string why = screenAndRead(file, folder, &text); !why.empty())
        throw Error(file.string() + ": " + why);
    return text;
}

}  // namespace pbrlab
