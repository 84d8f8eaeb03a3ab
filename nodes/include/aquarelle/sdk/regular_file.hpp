// Opening files that a graph, a mesh or the environment names, safely: only regular files are
// read (a FIFO blocks forever, /dev/zero and /dev/urandom never end), a path with a NUL
// character is refused instead of silently read up to the NUL, and every refusal says why in
// words (no such file, symlink loop, name too long, a FIFO...) naming the path and what it was
// for. Header-only and free of the host's types so plugins (the scene's mesh loader) share it.
#pragma once

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

namespace aq::files {

// What a path names, for messages.
inline const char* kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// Why `path` cannot be opened, in words, from an errno of stat/open.
inline std::string open_error_text(int error) {
  switch (error) {
    case ENOENT:
      return "no such file";
    case ELOOP:
      return "a loop of symbolic links";
    case ENAMETOOLONG:
      return "the name is too long";
    case EACCES:
      return "permission denied";
    case ENOTDIR:
      return "a part of the path is not a directory";
    default:
      return std::strerror(error);
  }
}

// Empty when `path` is a regular file that may be opened; else why not (one line, no
// trailing full stop), e.g. "it is a FIFO (named pipe); only regular files are read".
inline std::string regular_file_problem(const std::string& path) {
  if (path.find('\0') != std::string::npos) {
    return "the path contains a NUL character (a path cannot hold one)";
  }
  if (path.empty()) return "no path given";
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return open_error_text(errno);
  if (!S_ISREG(info.st_mode)) {
    return std::string("it is ") + kind_of(info.st_mode) + "; only regular files are read";
  }
  return "";
}

// An open descriptor of a regular file, or -1 and `why`. Opens without blocking (a FIFO that
// appears between a check and the open would otherwise hang) and checks the open file itself,
// so nothing can be swapped in between.
inline int open_regular_file(const std::string& path, std::string* why) {
  if (std::string problem = regular_file_problem(path); !problem.empty()) {
    *why = problem;
    return -1;
  }
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) {
    *why = open_error_text(errno);
    return -1;
  }
  struct stat info {};
  if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    *why = std::string("it is ") + kind_of(info.st_mode) + "; only regular files are read";
    ::close(fd);
    return -1;
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  return fd;
}

// Reads a whole regular file of at most `max_bytes`; false and `why` otherwise.
inline bool read_regular_file(const std::string& path, uint64_t max_bytes, std::string* text,
                              std::string* why) {
  const int fd = open_regular_file(path, why);
  if (fd < 0) return false;
  struct stat info {};
  ::fstat(fd, &info);
  if (static_cast<uint64_t>(info.st_size) > max_bytes) {
    *why = "it is " + std::to_string(info.st_size) + " bytes, more than the " +
           std::to_string(max_bytes) + " bytes allowed for this kind of file";
    ::close(fd);
    return false;
  }
  text->assign(static_cast<size_t>(info.st_size), '\0');
  size_t done = 0;
  while (done < text->size()) {
    const ssize_t n = ::read(fd, text->data() + done, text->size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // the file shrank while being read: keep what is there
    done += static_cast<size_t>(n);
  }
  text->resize(done);
  ::close(fd);
  return true;
}

// The size of a regular file, 0 when it cannot be had.
inline uint64_t regular_file_size(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0 || !S_ISREG(info.st_mode)) return 0;
  return static_cast<uint64_t>(info.st_size);
}

// How much memory one input file may make the process allocate (decoded pixels, mesh
// vertices): AQUARELLE_MEMORY_BUDGET_MB, 1024 MiB by default (a studio machine renders several
// frames at once; hostile files must stay well under a gigabyte). Declared sizes beyond it are
// refused before anything is allocated.
inline uint64_t memory_budget_bytes() {
  uint64_t megabytes = 1024;
  if (const char* text = std::getenv("AQUARELLE_MEMORY_BUDGET_MB"); text != nullptr) {
    char* end = nullptr;
    const unsigned long long value = std::strtoull(text, &end, 10);
    if (end != text && *end == '\0' && value > 0 && value < (1ull << 40)) megabytes = value;
  }
  return megabytes << 20;
}

}  // namespace aq::files
