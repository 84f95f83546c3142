#include "peer_flatten.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "core/elapsed.hpp"
#include "image_compare.hpp"

namespace acetate::bench {
namespace {

std::string quoted(const std::string& s) {
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// Runs a shell command, returns its exit status and everything it printed.
std::pair<int, std::string> run_captured(const std::string& command) {
    std::string output;
    FILE* pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return {-1, "popen failed"};
    char buffer[4096];
    while (size_t n = std::fread(buffer, 1, sizeof(buffer), pipe)) output.append(buffer, n);
    const int status = pclose(pipe);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

struct TileFile {
    int64_t width = 0, height = 0;
    bool integer = true;  // 8- or 16-bit: sRGB-encoded colour
};

TileFile tile_file(const TileDesc& tile) {
    TileFile out;
    if (auto in = OIIO::ImageInput::open(tile.image.string())) {
        out.width = in->spec().width;
        out.height = in->spec().height;
        const auto base = in->spec().format.basetype;
        out.integer = base != OIIO::TypeDesc::FLOAT && base != OIIO::TypeDesc::HALF &&
                      base != OIIO::TypeDesc::DOUBLE;
    }
    return out;
}

// The --over chain alone, in this process, through the library call oiiotool makes
// (ImageBufAlgo::over, on its threads): the tiles decoded and placed beforehand, untimed. The
// median of `runs`. (oiiotool --runstats rounds each operation to 10 ms: too coarse here.)
Result<double> time_over_chain(const SceneDesc& scene, int runs) {
    std::vector<OIIO::ImageBuf> tiles;  // bottom to top
    for (const FloorDesc& floor : scene.floors)
        for (const TileDesc& tile : floor.tiles) {
            OIIO::ImageBuf source(tile.image.string());
            if (!source.read(0, 0, true, OIIO::TypeDesc::FLOAT))
                return make_error(ErrorCode::ImageDecode,
                                  fmt::format("{}: {}", tile.image.string(), source.geterror()));
            OIIO::ImageBuf image = source;
            if (tile_file(tile).integer)
                image = OIIO::ImageBufAlgo::colorconvert(source, "sRGB", "linear", true);
            const int w = int(std::lround(tile.rect.width));
            const int h = int(std::lround(tile.rect.height));
            if (image.spec().width != w || image.spec().height != h)
                image = OIIO::ImageBufAlgo::resize(image, "", 0, OIIO::ROI(0, w, 0, h, 0, 1, 0, 4));
            image.set_origin(int(std::lround(tile.rect.x)), int(std::lround(tile.rect.y)));
            tiles.push_back(std::move(image));
        }
    const auto& bg = scene.background;
    const float background[4] = {bg[0] * bg[3], bg[1] * bg[3], bg[2] * bg[3], bg[3]};
    std::vector<double> times;
    for (int r = 0; r < std::max(runs, 1); ++r) {
        OIIO::ImageBuf canvas = OIIO::ImageBufAlgo::fill(
            background, OIIO::ROI(0, int(scene.width), 0, int(scene.height), 0, 1, 0, 4));
        const auto start = std::chrono::steady_clock::now();
        for (const OIIO::ImageBuf& tile : tiles) canvas = OIIO::ImageBufAlgo::over(tile, canvas);
        times.push_back(milliseconds_since(start));
    }
    std::sort(times.begin(), times.end());
    return times[times.size() / 2];
}

}  // namespace

std::string oiiotool_command(const SceneDesc& scene, const std::filesystem::path& output) {
    // oiiotool's `A B --over` puts A over B, so the stack is built top tile first, each lower
    // image joined under what is above it; the background ends it.
    std::string cmd = "oiiotool";
    bool first = true;
    for (size_t f = scene.floors.size(); f-- > 0;) {
        const FloorDesc& floor = scene.floors[f];
        for (size_t t = floor.tiles.size(); t-- > 0;) {
            const TileDesc& tile = floor.tiles[t];
            const TileFile file = tile_file(tile);
            cmd += fmt::format(" -i:type=float {}", quoted(tile.image.string()));
            // Decoded to linear light like acetate does: integer files are sRGB (colorconvert
            // unpremultiplies around the transfer), float files are linear already.
            if (file.integer) cmd += " --colorconvert:unpremult=1 sRGB linear";
            const int64_t w = std::lround(tile.rect.width), h = std::lround(tile.rect.height);
            // Resized only when the image is not already its rect's size (oiiotool's resize
            // filters even at scale 1).
            if (file.width != w || file.height != h) cmd += fmt::format(" --resize {}x{}", w, h);
            cmd += fmt::format(" --origin {:+}{:+}", int64_t(std::lround(tile.rect.x)),
                               int64_t(std::lround(tile.rect.y)));
            if (!first) cmd += " --over";
            first = false;
        }
    }
    const auto& bg = scene.background;  // straight alpha as written: premultiply it
    cmd += fmt::format(" --pattern constant:color={},{},{},{} {}x{} 4", bg[0] * bg[3],
                       bg[1] * bg[3], bg[2] * bg[3], bg[3], scene.width, scene.height);
    if (!first) cmd += " --over";
    cmd += fmt::format(" --cut {}x{}+0+0 -d float -o {}", scene.width, scene.height,
                       quoted(output.string()));
    return cmd;
}

Result<PeerComparison> flatten_with_oiiotool(const SceneDesc& scene,
                                             const AcetateFlattening& acetate,
                                             const std::filesystem::path& work_dir,
                                             const ErrorThresholds& thresholds, int runs) {
    if (run_captured("command -v oiiotool").first != 0)
        return make_error(ErrorCode::FileNotFound,
                          "oiiotool is not on PATH (Debian: openimageio-tools); no peer timing");
    const std::filesystem::path output = work_dir / "oiiotool-flattened.exr";
    PeerComparison out;
    out.scene = scene.file.string();
    out.tool = "oiiotool --over";
    out.command = oiiotool_command(scene, output);
    std::vector<double> run_ms;
    for (int i = 0; i < std::max(runs, 1); ++i) {
        const auto start = std::chrono::steady_clock::now();
        auto [status, printed] = run_captured(out.command);
        run_ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
        if (status != 0)
            return make_error(ErrorCode::InvalidInput,
                              fmt::format("oiiotool failed (exit {}): {}", status,
                                          printed.substr(0, printed.find('\n'))));
    }
    std::sort(run_ms.begin(), run_ms.end());
    out.tool_ms = run_ms[run_ms.size() / 2];
    auto over_ms = time_over_chain(scene, runs);
    if (!over_ms) return over_ms.error();
    out.tool_over_ms = over_ms.value();
    out.acetate_frame_ms = acetate.frame_ms;
    out.acetate_run_ms = acetate.run_ms;

    auto image = load_image(output, ImageRole::Colour);
    if (!image) return image.error();
    auto difference = compare_images(image.value(), acetate.image, thresholds);
    if (!difference) return difference.error();
    out.difference = difference.value();
    return out;
}

}  // namespace acetate::bench
