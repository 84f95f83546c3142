#pragma once
// Holds what third-party code prints on standard error while it runs. Image decoders (libpng
// through OpenImageIO) print their own raw lines before returning an error the project already
// reports in one line; capturing file descriptor 2 around the call keeps the one-line promise
// by construction, whatever the library. The caller decides what to do with the text: drop it
// when the failure is reported anyway, or pass it on in one line of its own.
//
// Process-wide while it lives (a file descriptor cannot be redirected per thread): use it around
// calls made at load, which run on one thread.

#include <string>

namespace acetate {

class StderrCapture {
  public:
    StderrCapture();   // redirects fd 2 into an in-memory file; does nothing if that fails
    ~StderrCapture();  // restores fd 2 if finish() was not called
    StderrCapture(const StderrCapture&) = delete;
    StderrCapture& operator=(const StderrCapture&) = delete;

    // Restores fd 2 and returns what was written meanwhile ("" if nothing, or if capturing
    // could not start).
    std::string finish();

  private:
    int saved_ = -1;    // the original fd 2
    int capture_ = -1;  // the in-memory file
};

}  // namespace acetate
