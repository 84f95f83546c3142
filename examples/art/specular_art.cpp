// specular_art: the masks acetate.specular reads in the harbour example, drawn procedurally.
//
// For three places that should shine at dusk:
// - the water's edge on the ground (ground_*): a wet band of sand, stone and wood along every
//   shore, and the shallow rim of the water, with small ripples in the normal map;
// - the slate roof of house B (roof_b_*): slates a little glossy, each row tilted where it
//   overlaps the next, the roof faces pitched; its glazed canopy is smooth glass;
// - the corrugated metal roof of the warehouse (roof_c_*): shiny metal, corrugations in the
//   normal map, rust (found in the drawn roof by its colour) dull and rough.
// House A's terracotta roof is left matte on purpose: no masks.
//
// Encodings (docs/plugins/specular.md): specular and roughness are one-channel 8-bit masks,
// 0..1; the normal mask is 8-bit RGB, (n + 1) / 2 per axis with green pointing up the image
// (OpenGL-style). Roof geometry repeats the boxes make_example_art.cpp draws them from.
#include "specular_art.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "art_math.hpp"

namespace {

// A fixed-seed integer hash to [0, 1), and smooth value noise from it.
float hash01(int x, int y, uint32_t seed) {
    uint32_t h = uint32_t(x) * 0x8da6b343u ^ uint32_t(y) * 0xd8163841u ^ seed * 0xcb1ab31fu;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    return float(h & 0xffffffu) / 16777216.f;
}
float noise(float x, float y, uint32_t seed) {
    int xi = int(std::floor(x)), yi = int(std::floor(y));
    float fx = smooth(0, 1, x - float(xi)), fy = smooth(0, 1, y - float(yi));
    float a = hash01(xi, yi, seed), b = hash01(xi + 1, yi, seed);
    float c = hash01(xi, yi + 1, seed), d = hash01(xi + 1, yi + 1, seed);
    return a + (b - a) * fx + (c - a) * fy + (a - b - c + d) * fx * fy;
}

// The three masks of one image, drawn per pixel.
struct Masks {
    int w, h;
    std::vector<float> specular, roughness;
    std::vector<std::array<float, 3>> normal;  // scene axes: x right, y down, z up
    Masks(int w_, int h_)
        : w(w_),
          h(h_),
          specular(size_t(w_) * size_t(h_), 0.f),
          roughness(size_t(w_) * size_t(h_), 1.f),
          normal(size_t(w_) * size_t(h_), std::array<float, 3>{0, 0, 1}) {}
    void set(int x, int y, float s, float r, float nx, float ny) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        const float len = std::sqrt(nx * nx + ny * ny + 1);
        specular[i] = clamp01(s), roughness[i] = clamp01(r);
        normal[i] = {nx / len, ny / len, 1 / len};
    }
};

bool save(const std::filesystem::path& path, int w, int h, int channels,
          const std::vector<uint8_t>& pixels) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out) return false;
    OIIO::ImageSpec spec(w, h, channels, OIIO::TypeDesc::UINT8);
    spec.attribute("png:compressionLevel", 9);
    bool ok =
        out->open(path.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels.data());
    ok = out->close() && ok;
    if (!ok)
        std::fprintf(stderr, "make_example_art: %s: %s\n", path.c_str(), out->geterror().c_str());
    return ok;
}

bool save_masks(const std::filesystem::path& dir, const std::string& stem, const Masks& m) {
    auto q8 = [](float v) { return uint8_t(std::lround(clamp01(v) * 255.f)); };
    const size_t n = size_t(m.w) * size_t(m.h);
    std::vector<uint8_t> s(n), r(n), rgb(n * 3);
    for (size_t i = 0; i < n; ++i) {
        s[i] = q8(m.specular[i]), r[i] = q8(m.roughness[i]);
        rgb[i * 3 + 0] = q8(0.5f + 0.5f * m.normal[i][0]);
        rgb[i * 3 + 1] = q8(0.5f - 0.5f * m.normal[i][1]);  // green up the image
        rgb[i * 3 + 2] = q8(0.5f + 0.5f * m.normal[i][2]);
    }
    return save(dir / (stem + "_Specular.png"), m.w, m.h, 1, s) &&
           save(dir / (stem + "_Roughness.png"), m.w, m.h, 1, r) &&
           save(dir / (stem + "_Normal.png"), m.w, m.h, 3, rgb);
}

// ---- the water's edge ---------------------------------------------------------------------
// A box blur of radius r along x then y (clamped at the borders).
std::vector<float> blur(std::vector<float> v, int w, int h, int r) {
    std::vector<float> t(v.size());
    for (int pass = 0; pass < 2; ++pass) {
        const bool along_x = pass == 0;
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                float sum = 0;
                for (int k = -r; k <= r; ++k) {
                    const int xx = along_x ? std::clamp(x + k, 0, w - 1) : x;
                    const int yy = along_x ? y : std::clamp(y + k, 0, h - 1);
                    sum += v[size_t(yy) * size_t(w) + size_t(xx)];
                }
                t[size_t(y) * size_t(w) + size_t(x)] = sum / float(2 * r + 1);
            }
        std::swap(v, t);
    }
    return v;
}

Masks water_edge(const ArtImage& water) {
    const int w = water.width, h = water.height;
    std::vector<float> wet(size_t(w) * size_t(h));
    for (size_t i = 0; i < wet.size(); ++i) wet[i] = water.rgba[i * 4];
    const std::vector<float> near = blur(blur(wet, w, h, 5), w, h, 5);
    Masks m(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = size_t(y) * size_t(w) + size_t(x);
            const float fx = float(x) + 0.5f, fy = float(y) + 0.5f;
            // Wet land within a few pixels of the water; the water's shallow rim.
            const float shore = (1 - wet[i]) * smooth(0.03f, 0.3f, near[i]);
            const float rim = wet[i] * (1 - smooth(0.55f, 0.9f, near[i]));
            const float patchy = 0.7f + 0.3f * noise(fx * 0.15f, fy * 0.15f, 3);
            // Ripples: a wave train bent by noise; its slope tilts the normal.
            const float phase = 0.7f * fx + 0.45f * fy + 6 * noise(fx * 0.02f, fy * 0.02f, 4);
            const float slope = 0.35f * std::cos(phase) * std::max(shore, rim);
            m.set(x, y, (0.75f * shore + 0.55f * rim) * patchy,
                  0.32f * (1 - rim) + 0.12f * rim + 0.1f * (1 - patchy), -0.7f * slope,
                  -0.45f * slope);
        }
    return m;
}

// ---- roofs --------------------------------------------------------------------------------
struct Box {
    float x0, y0, x1, y1;
    float sd(float x, float y) const {
        float dx = std::fabs(x - (x0 + x1) / 2) - (x1 - x0) / 2;
        float dy = std::fabs(y - (y0 + y1) / 2) - (y1 - y0) / 2;
        return std::hypot(std::max(dx, 0.f), std::max(dy, 0.f)) + std::min(std::max(dx, dy), 0.f);
    }
};
// A hipped (or gable) roof over `b` minus `cut`, as make_example_art.cpp draws it.
struct Shape {
    Box b, cut;
    bool gable;
    Box hole;
};
// Which face a point lies on: the direction downhill (towards its eave) and the height above
// that eave, t the coordinate along the eave.
struct Face {
    float nx, ny, height, along;
};
Face face(float x, float y, const Shape& r) {
    std::array<float, 4> e{x - r.b.x0, r.b.x1 - x, y - r.b.y0, r.b.y1 - y};
    if (r.gable) e[0] = e[1] = 1e9f;
    const int i = int(std::min_element(e.begin(), e.end()) - e.begin());
    const float dirs[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};
    Face f{dirs[i][0], dirs[i][1], e[size_t(i)], i < 2 ? y : x};
    const float qx = std::fabs(x - (r.cut.x0 + r.cut.x1) / 2) - (r.cut.x1 - r.cut.x0) / 2;
    const float qy = std::fabs(y - (r.cut.y0 + r.cut.y1) / 2) - (r.cut.y1 - r.cut.y0) / 2;
    const float q = std::max(qx, qy);
    if (q < f.height) {  // faces sloping down into the cut
        f.height = q;
        f.nx = qx > qy ? (x < r.cut.x0 ? 1.f : -1.f) : 0.f;
        f.ny = qx > qy ? 0.f : (y < r.cut.y0 ? 1.f : -1.f);
        f.along = qx > qy ? y : x;
    }
    return f;
}
float footprint(float x, float y, const Shape& r) {
    return std::max({r.b.sd(x, y), -r.cut.sd(x, y), -r.hole.sd(x, y)});
}

constexpr float kPitch = 0.55f;  // roof faces rise about 29 degrees

Masks slate_roof(const ArtImage& img) {
    const Shape shape{{11, 11, 165, 229}, {87, 99, 300, 300}, false, {40, 150, 58, 196}};
    const Box glass{84, 96, 160, 196};
    Masks m(img.width, img.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float fx = float(x) + 0.5f, fy = float(y) + 0.5f;
            const float dg = glass.sd(fx, fy);
            if (footprint(fx, fy, shape) > 0.5f && dg < 0.5f) {
                // The canopy: smooth glass panes, painted mullions (the same grid as drawn).
                const float u = fx - glass.x0, v = fy - glass.y0;
                const bool frame = dg > -2 || fract(u / 13) < 0.12f || fract(v / 25) < 0.07f;
                m.set(x, y, frame ? 0.25f : 1.f, frame ? 0.5f : 0.05f, 0, 0);
                continue;
            }
            if (footprint(fx, fy, shape) > 0.5f) continue;
            const Face f = face(fx, fy, shape);
            // Each row of slates (3 px) tilts a little more at its lower, overlapping edge;
            // each slate (6 px) has its own gloss.
            const float row = fract(std::max(f.height, 0.f) / 3);
            const int slate = int(std::floor(f.along / 6 + (int(f.height / 3) & 1) * 0.5f));
            const float gloss = hash01(slate, int(f.height / 3), 7);
            const float tilt = kPitch + 0.25f * (row - 0.5f);
            m.set(x, y, 0.3f + 0.25f * gloss, 0.45f - 0.15f * gloss, f.nx * tilt, f.ny * tilt);
        }
    return m;
}

Masks metal_roof(const ArtImage& img) {
    const Shape shape{{11, 11, 126, 101}, {-9, -9, -8, -8}, true, {40, 24, 70, 34}};
    Masks m(img.width, img.height);
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
            const float fx = float(x) + 0.5f, fy = float(y) + 0.5f;
            if (footprint(fx, fy, shape) > 0.5f) continue;
            const Face f = face(fx, fy, shape);
            // Rust, where the drawn roof is redder than it is blue; it does not shine.
            const float* p = &img.rgba[(size_t(y) * size_t(img.width) + size_t(x)) * 4];
            const float rust = p[3] > 0 ? smooth(-0.02f, 0.12f, (p[0] - p[2]) / p[3]) : 0.f;
            // Corrugations across the faces: height 0.3 sin(1.6 t), slope 0.48 cos(1.6 t).
            const float ridge = 0.48f * std::cos(1.6f * f.along);
            const float cx = f.ny != 0 ? -ridge : 0.f, cy = f.nx != 0 ? -ridge : 0.f;
            m.set(x, y, 0.6f * (1 - rust), 0.35f + 0.5f * rust, f.nx * kPitch + cx,
                  f.ny * kPitch + cy);
        }
    return m;
}

}  // namespace

bool write_specular_art(const std::filesystem::path& dir, const ArtImage& water,
                        const ArtImage& roof_b, const ArtImage& roof_c) {
    return save_masks(dir, "ground", water_edge(water)) &&
           save_masks(dir, "roof_b", slate_roof(roof_b)) &&
           save_masks(dir, "roof_c", metal_roof(roof_c));
}
