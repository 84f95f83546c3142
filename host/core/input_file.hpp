#pragma once
// Reading an input file whole, with the checks every input gets (docs/conventions.md, "Limits
// on inputs"): the file is opened without blocking (a FIFO given as a file name never stalls
// the open), only a regular file is read (a FIFO, a device, a directory or a socket is refused
// before a byte of it is read), its size is checked against a stated limit before reading, and
// every failure is one line naming the file as given:
//   `<file>: file not found`                                             FileNotFound
//   `<file>: not a regular file (a FIFO)`, `(a character device)`, ...   InvalidInput
//   `<file>: 3.5 GiB (3758096384 bytes) is over the 64 MiB limit for a registry`  InvalidInput
//   `<file>: <what failed>: <strerror>`, e.g. `<file>: cannot open: File name too long`  Io

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "core/result.hpp"

namespace acetate {

// The largest scene file read. A scene lists tiles, lights and effects, not pixels: a tile is
// about 100 bytes, so 16 MiB holds some 150,000 tiles, far beyond what a scene can usefully
// draw, while nlohmann's document (up to ~18 times the text for a hostile array of small
// numbers) stays under 300 MB.
inline constexpr std::uint64_t kMaxSceneFileBytes = std::uint64_t(16) << 20;
// The largest registry or sign-offs file read. Records accumulate per plugin version and hold
// free-text notes, and they are never pruned, so it is allowed more room than a scene; the
// largest real one is a few KiB.
inline constexpr std::uint64_t kMaxRegistryFileBytes = std::uint64_t(64) << 20;
// The largest JSON file the harness exchanges with its children (a plugin's description, a
// case, a case's result). Each is a few KiB; a child runs plugin code, so what it wrote is
// read as untrusted input.
inline constexpr std::uint64_t kMaxHarnessFileBytes = std::uint64_t(64) << 20;

// The largest image file read (a tile, a mask, a report's picture). A 16384x16384 RGBA image
// (the largest canvas a device allows) is 1 GiB as uncompressed 32-bit float EXR; a file beyond
// that is not an image the host could draw.
inline constexpr std::uint64_t kMaxImageFileBytes = std::uint64_t(1) << 30;

// The largest pipeline cache read: the driver's data for every pipeline the project makes is a
// few MiB on real GPUs (32 bytes on lavapipe); a larger file is not ours.
inline constexpr std::uint64_t kMaxPipelineCacheBytes = std::uint64_t(256) << 20;

// The bytes of `file`, at most `max_bytes` of them. `what` names the kind of file for the
// size message, with its article: "a scene file", "a registry".
Result<std::string> read_input_file(const std::filesystem::path& file, std::uint64_t max_bytes,
                                    std::string_view what);

// Same, but a file that does not exist (ENOENT) is nullopt rather than an error.
Result<std::optional<std::string>> read_input_file_if_exists(const std::filesystem::path& file,
                                                             std::uint64_t max_bytes,
                                                             std::string_view what);

// "17 bytes", "64 MiB", "3.5 GiB (3758096384 bytes)": binary units, exact byte count added
// when the unit rounds.
std::string describe_byte_count(std::uint64_t bytes);

}  // namespace acetate
