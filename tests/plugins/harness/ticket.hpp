#pragma once
// A numbered ticket in the folder $ACETATE_TEST_FLAKY_DIR, taken once per call: the first call
// of a whole test run gets 1, the next 2, ... (each file created exclusively, so concurrent
// processes never share a number). `flaky` and `slow_first_build` misbehave on ticket 1 only.
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <string>

// The number of the ticket this call took; 0 without the folder.
inline int take_ticket() {
    const char* folder = std::getenv("ACETATE_TEST_FLAKY_DIR");
    if (!folder) return 0;
    for (int n = 1; n < 100000; ++n) {
        const std::string file = std::string(folder) + "/ticket-" + std::to_string(n);
        const int fd = ::open(file.c_str(), O_CREAT | O_EXCL | O_WRONLY, 0644);
        if (fd >= 0) {
            ::close(fd);
            return n;
        }
        if (errno != EEXIST) return 0;
    }
    return 0;
}
