#include "core/stderr_capture.hpp"

#include <sys/mman.h>
#include <unistd.h>

#include <cstdio>

namespace acetate {

StderrCapture::StderrCapture() {
    std::fflush(stderr);
    capture_ = ::memfd_create("acetate-stderr", MFD_CLOEXEC);
    if (capture_ < 0) return;
    saved_ = ::dup(STDERR_FILENO);
    if (saved_ < 0 || ::dup2(capture_, STDERR_FILENO) < 0) {
        if (saved_ >= 0) ::close(saved_);
        ::close(capture_);
        saved_ = capture_ = -1;
    }
}

std::string StderrCapture::finish() {
    if (saved_ < 0) return "";
    std::fflush(stderr);
    ::dup2(saved_, STDERR_FILENO);
    ::close(saved_);
    saved_ = -1;
    std::string text;
    char buffer[4096];
    // Keep at most 64 KiB: the text only ever becomes one line of a message.
    for (off_t at = 0; text.size() < (64u << 10);) {
        const ssize_t n = ::pread(capture_, buffer, sizeof(buffer), at);
        if (n <= 0) break;
        text.append(buffer, size_t(n));
        at += n;
    }
    ::close(capture_);
    capture_ = -1;
    return text;
}

StderrCapture::~StderrCapture() {
    (void)finish();
}

}  // namespace acetate
