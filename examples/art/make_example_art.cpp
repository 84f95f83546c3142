// make_example_art: draws the images of the bundled "harbour" example scene procedurally.
//
//   acetate-make-example-art <output-folder>
//
// Every image is computed per pixel from signed distance functions and a fixed-seed hash
// noise, so each run writes byte-identical files. Output: 8-bit sRGB PNGs with straight
// (unassociated) alpha; ground_Water.png is a one-channel mask, white where water is.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "art_math.hpp"
#include "specular_art.hpp"  // the masks acetate.specular reads

namespace {

struct Col {
    float r, g, b;
    Col operator*(float k) const { return {r * k, g * k, b * k}; }
    Col operator+(Col o) const { return {r + o.r, g + o.g, b + o.b}; }
};
Col mix(Col a, Col b, float t) {
    return a * (1 - t) + b * t;
}

// ---- deterministic noise ---------------------------------------------------------------
float hash(int x, int y, uint32_t seed) {
    uint32_t h = uint32_t(x) * 374761393u + uint32_t(y) * 668265263u + seed * 2246822519u;
    h = (h ^ (h >> 13)) * 1274126177u;
    return float((h ^ (h >> 16)) & 0xffffffu) / 16777216.f;
}
float vnoise(float x, float y, uint32_t s) {
    int xi = int(std::floor(x)), yi = int(std::floor(y));
    float fx = x - float(xi), fy = y - float(yi);
    fx = fx * fx * (3 - 2 * fx), fy = fy * fy * (3 - 2 * fy);
    float a = hash(xi, yi, s), b = hash(xi + 1, yi, s), c = hash(xi, yi + 1, s),
          d = hash(xi + 1, yi + 1, s);
    return a + (b - a) * fx + (c - a) * fy + (a - b - c + d) * fx * fy;
}
float fbm(float x, float y, uint32_t s, int octaves = 4) {
    float sum = 0, amp = 0.5f, norm = 0;
    for (int i = 0; i < octaves; ++i) {
        sum += amp * vnoise(x, y, s + uint32_t(i) * 101u), norm += amp;
        x *= 2.03f, y *= 2.03f, amp *= 0.5f;
    }
    return sum / norm;
}

// ---- shapes ------------------------------------------------------------------------------
struct Box {
    float x0, y0, x1, y1;
};
using Pt = std::array<float, 2>;
float sdBox(float px, float py, Box b) {
    float dx = std::fabs(px - (b.x0 + b.x1) / 2) - (b.x1 - b.x0) / 2;
    float dy = std::fabs(py - (b.y0 + b.y1) / 2) - (b.y1 - b.y0) / 2;
    return std::hypot(std::max(dx, 0.f), std::max(dy, 0.f)) + std::min(std::max(dx, dy), 0.f);
}
float sdPoly(float px, float py, const std::vector<Pt>& pts) {
    float d = 1e9f;
    for (size_t i = 0; i + 1 < pts.size(); ++i) {
        float ax = pts[i][0], ay = pts[i][1], bx = pts[i + 1][0] - ax, by = pts[i + 1][1] - ay;
        float t = clamp01(((px - ax) * bx + (py - ay) * by) / (bx * bx + by * by));
        d = std::min(d, std::hypot(px - ax - t * bx, py - ay - t * by));
    }
    return d;
}
// Staggered blocks (bricks, flagstones, roof tiles) of bw x bh: a tint per block, darker joints.
float blocks(float u, float v, float bw, float bh, float spread, uint32_t seed) {
    int row = int(std::floor(v / bh));
    float s = u / bw + float(row & 1) * 0.5f,
          k = 1 - spread / 2 + spread * hash(int(std::floor(s)), row, seed);
    return fract(s) < 0.12f || fract(v / bh) < 0.15f ? k * 0.75f : k;
}
// Coverage of a shape at signed distance sd: a linear alpha ramp 2*soft pixels wide.
float cover(float sd, float soft = 0.8f) {
    return clamp01(0.5f - sd / (2 * soft));
}

// ---- images (premultiplied while drawing, straight alpha when written) --------------------
struct Px {
    float* q;
    void over(Col c, float a) {
        const float src[4] = {c.r * a, c.g * a, c.b * a, a};
        for (int i = 0; i < 4; ++i) q[i] = src[i] + q[i] * (1 - a);
    }
};
struct Img {
    int w, h;
    std::vector<float> p;
    Img(int w_, int h_) : w(w_), h(h_), p(size_t(w_) * size_t(h_) * 4, 0.f) {}
    template <class F>
    void paint(F f) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                f(float(x) + 0.5f, float(y) + 0.5f,
                  Px{&p[(size_t(y) * size_t(w) + size_t(x)) * 4]});
    }
};

bool save(const std::filesystem::path& path, const Img& img, bool grey = false) {
    const int ch = grey ? 1 : 4;
    std::vector<uint8_t> out(size_t(img.w) * size_t(img.h) * size_t(ch));
    auto q8 = [](float v) { return uint8_t(std::lround(clamp01(v) * 255.f)); };
    for (size_t i = 0; i < size_t(img.w) * size_t(img.h); ++i) {
        const float* s = &img.p[i * 4];  // grey: the mask value is kept in the red channel
        for (int c = 0; c < ch; ++c)
            out[i * size_t(ch) + size_t(c)] = grey || c == 3 ? q8(s[c])
                                              : s[3] > 0     ? q8(s[c] / s[3])
                                                             : 0;
    }
    auto o = OIIO::ImageOutput::create(path.string());
    if (!o) return false;
    OIIO::ImageSpec spec(img.w, img.h, ch, OIIO::TypeDesc::UINT8);
    spec.attribute("oiio:ColorSpace", "sRGB");
    spec.attribute("png:compressionLevel", 9);
    if (!grey) spec.attribute("oiio:UnassociatedAlpha", 1);
    bool ok = o->open(path.string(), spec) && o->write_image(OIIO::TypeDesc::UINT8, out.data());
    ok = o->close() && ok;
    if (!ok)
        std::fprintf(stderr, "make_example_art: %s: %s\n", path.c_str(), o->geterror().c_str());
    return ok;
}

// ---- floor 0: ground ----------------------------------------------------------------------
const Box kQuay{520, 474, 905, 540};
const Box kPier{700, 532, 728, 668};
const Box kBridge{975, 314, 1095, 342};
const std::vector<Box> kFields{{1092, 24, 1222, 150}, {1092, 162, 1222, 262}, {560, 150, 640, 250}};
const std::vector<Pt> kRiver{{1005, -30}, {985, 110}, {1045, 250}, {1020, 390}, {1075, 540}};
const std::vector<std::vector<Pt>> kPaths{
    {{-20, 408}, {150, 414}, {326, 384}, {326, 340}},  // west road to house A
    {{326, 384}, {500, 402}, {556, 478}},              // to the warehouse quay
    {{500, 402}, {620, 330}, {708, 302}, {708, 286}},  // up to house B
    {{708, 302}, {900, 318}, {1260, 326}},             // east road over the bridge
    {{540, 470}, {430, 560}, {300, 600}},              // down to the pond
};

float shoreY(float x) {
    return 770 - 250 * smooth(400, 660, x) + 24 * (fbm(x * 0.012f, 3.f, 7) - 0.5f);
}
float sdBoat(float x, float y) {  // a rowing boat: the lens between two circles
    float dx = x - 822, dy = y - 606;
    return std::max(std::hypot(dx, dy - 70) - 82, std::hypot(dx, dy + 70) - 82);
}
float waterSd(float x, float y) {
    float sea = shoreY(x) - y;
    float river = sdPoly(x, y, kRiver) - (19 + 8 * fbm(x * 0.02f, y * 0.02f, 11));
    float pond = std::hypot(x - 232, (y - 612) * 1.35f) - 58 - 14 * fbm(x * 0.03f, y * 0.03f, 12);
    return std::max(std::min({sea, river, pond}), -sdBox(x, y, kQuay));
}

// Planks running across the short side of a box (pier, bridge), with dark joints.
Col planks(float x, float y, Box b, uint32_t seed) {
    bool alongX = (b.x1 - b.x0) > (b.y1 - b.y0);
    float u = alongX ? x : y, v = alongX ? y : x;
    int i = int(std::floor(u / 5));
    float k =
        (0.82f + 0.25f * hash(i, 0, seed)) * (0.92f + 0.12f * fbm(u * 0.3f, v * 0.05f, seed, 2));
    if (fract(u / 5) < 0.2f) k *= 0.55f;
    return Col{0.52f, 0.37f, 0.23f} * k;
}

void drawGround(Img& g, Img& mask) {
    g.paint([&](float x, float y, Px px) {
        float w = waterSd(x, y);
        // grass with a broad and a fine noise layer, plus sparse flowers/stones
        float n = fbm(x * 0.012f, y * 0.012f, 1), n2 = fbm(x * 0.09f, y * 0.09f, 2, 3);
        Col land = mix({0.27f, 0.42f, 0.18f}, {0.46f, 0.57f, 0.25f}, smooth(0.3f, 0.7f, n)) *
                   (0.88f + 0.24f * n2);
        float dirt = smooth(0.55f, 0.75f, fbm(x * 0.006f + 9, y * 0.006f, 3));
        land = mix(land, Col{0.50f, 0.43f, 0.30f} * (0.9f + 0.2f * n2), 0.6f * dirt);
        if (hash(int(x / 2), int(y / 2), 4) > 0.9985f) land = {0.86f, 0.82f, 0.55f};
        // sand fringe along all water
        float sandW = 7 + 10 * fbm(x * 0.03f, y * 0.03f, 5);
        Col sand = Col{0.80f, 0.72f, 0.52f} * (0.92f + 0.12f * n2);
        land = mix(sand, land, smooth(sandW - 2, sandW + 2, w));
        // paths with darker ruts and a shaded rim
        float dp = 1e9f;
        for (const auto& p : kPaths) dp = std::min(dp, sdPoly(x, y, p) - 8);
        Col path = Col{0.62f, 0.50f, 0.35f} * (0.9f + 0.18f * fbm(x * 0.2f, y * 0.2f, 6, 2));
        path = path * (1 - 0.12f * smooth(-4, -2.5f, dp) * (1 - smooth(-2.5f, -1, dp)));
        land = land * (1 - 0.25f * smooth(-3, 0, dp) * (1 - smooth(0, 3, dp)));
        land = mix(land, path, cover(dp, 1.2f));
        // fields: furrows alternating with green rows, inside a darker hedge line
        for (size_t i = 0; i < kFields.size(); ++i) {
            float df = sdBox(x, y, kFields[i]) + 3;
            float rows = fract((i == 1 ? x : y) / 7),
                  k = smooth(0.3f, 0.5f, rows) * smooth(0.9f, 0.7f, rows);
            Col crop = mix(Col{0.47f, 0.36f, 0.24f},
                           i == 1 ? Col{0.78f, 0.68f, 0.34f} : Col{0.38f, 0.58f, 0.22f}, k);
            crop = mix(crop * (0.9f + 0.2f * n2), Col{0.2f, 0.32f, 0.14f}, smooth(-3.5f, -2, df));
            land = mix(land, crop, cover(df, 1.f));
        }
        // quay paving: staggered stone blocks
        float dq = sdBox(x, y, kQuay);
        Col st = Col{0.60f, 0.58f, 0.53f} * blocks(x, y, 12, 7, 0.22f, 8);
        if (y > kQuay.y1 - 5)
            st = Col{0.48f, 0.46f, 0.43f} * (fract(x / 9) < 0.12f ? 0.7f : 1.f);  // kerb
        land = mix(land, st, cover(dq, 0.6f));
        // Under the water, only its bed: wet sand giving way to dark silt, pebbles and weed.
        // acetate.water (see the scene) adds the water itself: depth, waves, caustics, foam.
        float depth = smooth(0, 70, -w);
        float pebbles = fbm(x * 0.11f, y * 0.11f, 9, 3), weed = fbm(x * 0.02f, y * 0.035f, 10);
        Col water = mix(Col{0.62f, 0.55f, 0.40f}, Col{0.30f, 0.28f, 0.22f}, depth) *
                    (0.85f + 0.3f * pebbles);
        water = mix(water, Col{0.22f, 0.30f, 0.16f}, 0.5f * depth * smooth(0.55f, 0.7f, weed));
        float wa = cover(w, 0.8f);
        Col c = mix(land, water, wa);
        // pier and bridge: shadow on the water, then planks
        float ds = std::min(
            {sdBox(x - 4, y - 5, kPier), sdBox(x - 4, y - 5, kBridge), sdBoat(x - 4, y - 5)});
        c = c * (1 - 0.35f * wa * cover(ds, 2.5f));
        float dpi = sdBox(x, y, kPier), dbr = sdBox(x, y, kBridge);
        float wood = std::max(cover(dpi, 0.6f), cover(dbr, 0.6f));
        Col pl = dpi < dbr ? planks(x, y, kPier, 13) : planks(x, y, kBridge, 14);
        pl = pl * (1 - 0.4f * smooth(-2, 0, std::min(dpi, dbr)));
        c = mix(c, pl, wood);
        float db = sdBoat(x, y), rim = smooth(-3.5f, -2.5f, db) * smooth(-0.5f, -1.5f, db);
        Col hull = mix(Col{0.70f, 0.52f, 0.32f} * (fract(y / 4) < 0.2f ? 0.8f : 1.f),
                       {0.35f, 0.22f, 0.14f}, rim);
        if (std::fabs(x - 812) < 2 || std::fabs(x - 832) < 2)
            hull = {0.45f, 0.31f, 0.19f};  // benches
        c = mix(c, hull, cover(db, 0.6f));
        wood = std::max(wood, cover(db, 0.6f));
        px.over(c, 1);
        mask.p[(size_t(y) * size_t(mask.w) + size_t(x)) * 4] = wa * (1 - wood);
    });
}

// Two braziers at the quay's ends and a campfire by the pond: iron bowls (or a ring of stones)
// holding coals, and the fire mask acetate.fire burns from (white on the coals).
void drawFires(Img& g, Img& mask) {
    struct Fire {
        float x, y, r;
        bool stones;
    };
    const Fire fires[] = {{536, 490, 7, false}, {889, 490, 7, false}, {318, 560, 9, true}};
    g.paint([&](float x, float y, Px px) {
        for (const Fire& f : fires) {
            const float d = std::hypot(x - f.x, y - f.y);
            const Col rim =
                f.stones ? Col{0.45f, 0.43f, 0.40f} * (0.8f + 0.3f * hash(int(x), int(y), 31))
                         : Col{0.16f, 0.15f, 0.15f};
            px.over(rim, cover(d - f.r - 3, 0.8f));
            px.over(Col{0.10f, 0.06f, 0.04f} +
                        Col{0.35f, 0.10f, 0.02f} * fbm(x * 0.5f, y * 0.5f, 32, 2),
                    cover(d - f.r, 0.6f));
        }
    });
    mask.paint([&](float x, float y, Px px) {
        float m = 0;
        for (const Fire& f : fires)
            m = std::max(m, cover(std::hypot(x - f.x, y - f.y) - f.r + 1, 0.8f));
        px.q[0] = m;  // grey: the mask value is kept in the red channel
    });
}

// ---- floor 1: walls -----------------------------------------------------------------------
enum class Floor { Wood, Flag, Checker, Boards };
struct Room {
    Box b;
    Floor f;
    Col tint;
};
struct Building {
    std::vector<Room> rooms;  // later rooms win where they overlap
    std::vector<Box> walls;
    std::vector<Box> holes;  // open courtyards: fully transparent
    std::vector<Box> crates;
};

Col floorCol(const Room& r, float x, float y, uint32_t seed) {
    switch (r.f) {
        case Floor::Wood: {
            int row = int(std::floor(y / 4));
            int pl = int(std::floor((x + hash(row, 0, seed) * 20) / 18));
            float k = (0.85f + 0.25f * hash(pl, row, seed + 1)) *
                      (0.9f + 0.15f * fbm(x * 0.3f, y * 2, seed + 2, 2));
            if (fract(y / 4) < 0.22f) k *= 0.7f;
            return r.tint * k;
        }
        case Floor::Flag:
            return r.tint * blocks(x, y, 9, 9, 0.22f, seed);
        case Floor::Checker:
            return r.tint * ((int(std::floor(x / 6)) + int(std::floor(y / 6))) & 1 ? 1.f : 0.55f);
        case Floor::Boards: {
            float k = (0.85f + 0.2f * hash(int(std::floor(x / 8)), 0, seed)) *
                      (0.9f + 0.15f * fbm(x * 0.5f, y * 0.08f, seed, 2));
            return r.tint * (fract(x / 8) < 0.12f ? 0.7f * k : k);
        }
    }
    return r.tint;
}

Img drawWalls(int w, int h, const Building& b, uint32_t seed) {
    Img img(w, h);
    auto foot = [&](float x, float y) {
        float d = 1e9f;
        for (const auto& r : b.rooms) d = std::min(d, sdBox(x, y, r.b));
        for (const auto& w : b.walls) d = std::min(d, sdBox(x, y, w));
        for (const auto& h : b.holes) d = std::max(d, -sdBox(x, y, h));
        return d;
    };
    img.paint([&](float x, float y, Px px) {
        px.over({0, 0, 0}, 0.35f * cover(foot(x - 3, y - 4), 2.5f));
        float d = foot(x, y);
        if (d > 1) return;
        float dw = 1e9f;
        for (const auto& w : b.walls) dw = std::min(dw, sdBox(x, y, w));
        Col fc{0.5f, 0.5f, 0.5f};
        for (const auto& r : b.rooms)
            if (sdBox(x, y, r.b) <= 0.5f) fc = floorCol(r, x, y, seed);
        for (const auto& c : b.crates) {
            float dc = sdBox(x, y, c);
            float diag = std::min(std::fabs((x - c.x0) - (y - c.y0)),
                                  std::fabs((x - c.x0) + (y - c.y0) - (c.x1 - c.x0)));
            Col cc = Col{0.66f, 0.50f, 0.30f} * (dc > -1.5f || diag < 1 ? 0.6f : 1.f);
            fc = mix(fc * (1 - 0.4f * cover(sdBox(x - 2, y - 2, c), 1.5f)), cc, cover(dc, 0.5f));
        }
        fc = fc * (0.65f + 0.35f * smooth(0, 5, dw));  // ambient occlusion next to walls
        Col wc = Col{0.64f, 0.60f, 0.54f} * blocks(x, y, 5, 3, 0.3f, seed) *
                 (1 - 0.4f * smooth(-1.6f, -0.3f, dw));
        Col c = mix(fc, wc, cover(dw, 0.5f));
        c = c * (1 - 0.45f * smooth(-1.8f, -0.2f, d));  // dark outline along the footprint
        px.over(c, cover(d));
    });
    return img;
}

// ---- floor 2: roofs -----------------------------------------------------------------------
enum class RoofTex { Tiles, Slate, Metal };
// A hipped (or, with `gable`, ridged along x) roof over box `b` minus box `cut`: a courtyard or the
// missing corner of an L. The slope height at a point is its distance to the nearest eave line.
struct Roof {
    Box b, cut;
    bool gable;
    std::vector<Box> holes;  // skylights, with a frame drawn around them
    RoofTex tex;
    Col base;
    std::vector<Box> glass;  // semi-transparent glazing, drawn beneath the roof
};

Img drawRoof(int w, int h, const Roof& rf, uint32_t seed) {
    Img img(w, h);
    auto foot = [&](float x, float y) {
        float d = std::max(sdBox(x, y, rf.b), -sdBox(x, y, rf.cut));
        for (const auto& h : rf.holes) d = std::max(d, -sdBox(x, y, h));
        return d;
    };
    img.paint([&](float x, float y, Px px) {
        float sh = cover(foot(x - 4, y - 5), 3.f);
        for (const auto& g : rf.glass)  // the glass casts a faint shadow beside itself only
            sh = std::max(
                sh, 0.4f * cover(sdBox(x - 4, y - 5, g), 3.f) * (1 - cover(sdBox(x, y, g), 0.6f)));
        px.over({0, 0, 0}, 0.4f * sh);
        for (const auto& g : rf.glass) {  // glazing: panes at alpha 0.5, opaque mullions
            float dg = sdBox(x, y, g);
            if (dg > 1) continue;
            float u = x - g.x0, v = y - g.y0, r = fract((u + v) / 60);
            bool frame = dg > -2 || fract(u / 13) < 0.12f || fract(v / 25) < 0.07f;
            Col pane = mix({0.55f, 0.74f, 0.84f}, {0.86f, 0.94f, 0.98f},
                           0.2f + 0.6f * smooth(0.35f, 0.5f, r) * smooth(0.7f, 0.5f, r));
            px.over(frame ? Col{0.88f, 0.88f, 0.84f} : pane,
                    cover(dg, 0.6f) * (frame ? 1.f : 0.5f));
        }
        float d = foot(x, y);
        if (d > 1) return;
        std::array<float, 4> e{x - rf.b.x0, rf.b.x1 - x, y - rf.b.y0, rf.b.y1 - y};
        if (rf.gable) e[0] = e[1] = 1e9f;
        int i = int(std::min_element(e.begin(), e.end()) - e.begin());
        float h = e[size_t(i)];
        e[size_t(i)] = 1e9f;
        float crease = *std::min_element(e.begin(), e.end()) - h, valley = 1e9f;
        const float dirs[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};  // downhill, toward the eave
        float nx = dirs[i][0], ny = dirs[i][1], t = i < 2 ? y : x;
        float qx = std::fabs(x - (rf.cut.x0 + rf.cut.x1) / 2) - (rf.cut.x1 - rf.cut.x0) / 2;
        float qy = std::fabs(y - (rf.cut.y0 + rf.cut.y1) / 2) - (rf.cut.y1 - rf.cut.y0) / 2;
        float q = std::max(qx, qy);  // faces sloping down into the cut
        if (q < h) {
            crease = h - q, valley = std::fabs(qx - qy), h = q;
            nx = qx > qy ? (x < rf.cut.x0 ? 1.f : -1.f) : 0.f;
            ny = qx > qy ? 0.f : (y < rf.cut.y0 ? 1.f : -1.f);
            t = qx > qy ? y : x;
        } else
            crease = std::min(crease, q - h);
        float s = std::max(h, 0.f), k = 1;
        if (rf.tex == RoofTex::Metal) {
            k = 0.86f + 0.14f * std::sin(t * 1.6f);
        } else {
            float rowH = rf.tex == RoofTex::Tiles ? 3.5f : 3.f;
            k = blocks(t, s, rf.tex == RoofTex::Tiles ? 4.5f : 6.f, rowH, 0.22f, seed) *
                (0.8f + 0.25f * smooth(0, 0.5f, fract(s / rowH)));
        }
        Col c = rf.base * k * (0.92f + 0.12f * fbm(x * 0.08f, y * 0.08f, seed + 5, 3));
        if (rf.tex == RoofTex::Metal)  // a little rust
            c = mix(c, Col{0.52f, 0.36f, 0.24f},
                    0.35f * smooth(0.68f, 0.85f, fbm(x * 0.04f, y * 0.04f, seed + 6)));
        c = c * (0.84f + 0.24f * (-0.6f * nx - 0.8f * ny));
        c = c * (1 + 0.25f * smooth(1.2f, 0.3f, crease));  // hips and ridges catch the light
        c = c * (1 - 0.35f * smooth(1.2f, 0.3f, valley));  // valleys are in shade
        float dh = 1e9f;
        for (const auto& hb : rf.holes) dh = std::min(dh, sdBox(x, y, hb));
        c = mix(c, Col{0.36f, 0.27f, 0.2f}, smooth(2.6f, 1.8f, dh));  // skylight frames
        c = c * (1 - 0.5f * smooth(-1.8f, -0.2f, d));
        px.over(c, cover(d));
    });
    return img;
}

// ---- floor 3: tree crowns -------------------------------------------------------------------
struct Crown {
    float cx, cy, r;
    uint32_t seed;
};
float sdCrown(float x, float y, const Crown& c) {
    float dx = x - c.cx, dy = y - c.cy, d = std::hypot(dx, dy), a = std::atan2(dy, dx);
    float wob = fbm(std::cos(a) * 3 + 10, std::sin(a) * 3 + 10, c.seed, 2) +
                0.25f * std::sin(a * 7 + float(c.seed));
    return d - c.r * (0.84f + 0.16f * wob) - 4 * (fbm(x * 0.25f, y * 0.25f, c.seed + 1, 2) - 0.5f);
}
Img drawTrees(int w, int h, const std::vector<Crown>& crowns) {
    Img img(w, h);
    img.paint([&](float x, float y, Px px) {
        float sh = 0;
        for (const auto& c : crowns) sh = std::max(sh, cover(sdCrown(x - 7, y - 9, c), 4.f));
        px.over({0, 0, 0.02f}, 0.35f * sh);
        for (const auto& c : crowns) {
            float sd = sdCrown(x, y, c);
            if (sd > 2) continue;
            float nx = (x - c.cx) / c.r, ny = (y - c.cy) / c.r,
                  nz = std::sqrt(std::max(0.f, 1 - nx * nx - ny * ny));
            float lam = -0.5f * nx - 0.6f * ny + 0.62f * nz;
            float clump = fbm(x * 0.13f, y * 0.13f, c.seed + 2, 3);
            float leaf = smooth(0.55f, 0.8f, vnoise(x * 0.3f, y * 0.3f, c.seed + 3)) * 0.25f;
            Col col = mix({0.11f, 0.27f, 0.10f}, {0.52f, 0.68f, 0.28f},
                          clamp01(0.55f * lam + 0.9f * (clump - 0.5f) + 0.15f + leaf));
            col = col * (1 - 0.35f * smooth(-4, 0, sd));
            px.over(col, cover(sd, 1.5f));
        }
    });
    return img;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: %s <output-folder>\n", argv[0]);
        return 2;
    }
    const std::filesystem::path dir = argv[1];
    std::filesystem::create_directories(dir);
    bool ok = true;

    Img ground(1280, 720), water(1280, 720), fire(1280, 720);
    drawGround(ground, water);
    drawFires(ground, fire);
    ok &= save(dir / "ground.png", ground) && save(dir / "ground_Water.png", water, true) &&
          save(dir / "ground_Fire.png", fire, true);

    // Building data, in image pixels: rooms (floor boxes), walls, courtyard holes, crates.
    // clang-format off
    // House A: courtyard house, 256x192, drawn at 1.375x. The courtyard is open to the sky.
    const Col oak{0.62f, 0.43f, 0.26f}, flag{0.70f, 0.66f, 0.60f};
    Building a{{{{14, 14, 242, 178}, Floor::Wood, oak}, {{14, 14, 93, 178}, Floor::Flag, flag},
                {{163, 99, 242, 178}, Floor::Wood, Col{0.55f, 0.36f, 0.22f}}},
               {{14, 14, 242, 20}, {14, 172, 118, 178}, {138, 172, 242, 178}, {14, 14, 20, 178},
                {236, 14, 242, 178}, {90, 64, 166, 70}, {90, 122, 118, 128}, {138, 122, 166, 128},
                {90, 64, 96, 128}, {160, 64, 166, 128}, {90, 14, 96, 30}, {90, 44, 96, 64},
                {90, 128, 96, 150}, {90, 162, 96, 178}, {166, 96, 190, 102}, {210, 96, 242, 102},
                {160, 14, 166, 64}},
               {{96, 70, 160, 122}},
               {{26, 140, 38, 152}, {40, 142, 50, 152}, {26, 154, 36, 164}}};
    Roof ra{{11, 11, 245, 181}, {99, 73, 157, 119}, false, {{192, 30, 214, 46}}, RoofTex::Tiles,
            {0.72f, 0.34f, 0.22f}, {}};

    // House B: L-shaped house with a glazed conservatory in the inner corner, 176x240 at 1:1.
    Building b{{{{14, 14, 162, 96}, Floor::Wood, oak}, {{14, 96, 84, 226}, Floor::Flag, flag},
                {{84, 96, 160, 196}, Floor::Checker, Col{0.85f, 0.82f, 0.76f}}},
               {{14, 14, 162, 20}, {14, 14, 20, 226}, {156, 14, 162, 96}, {14, 220, 40, 226},
                {56, 220, 84, 226}, {78, 96, 84, 130}, {78, 150, 84, 226}, {84, 90, 120, 96},
                {136, 90, 162, 96}, {20, 120, 78, 126}, {84, 20, 90, 70}, {84, 193, 160, 196},
                {157, 96, 160, 196}},
               {}, {}};
    Roof rb{{11, 11, 165, 229}, {87, 99, 300, 300}, false, {{40, 150, 58, 196}}, RoofTex::Slate,
            {0.40f, 0.44f, 0.52f}, {{84, 96, 160, 196}}};

    // Warehouse on the quay: 192x112 at 1.25x; the right bay is an open loading yard.
    Building c{{{{14, 14, 178, 98}, Floor::Boards, Col{0.58f, 0.47f, 0.34f}},
                {{126, 20, 172, 92}, Floor::Flag, Col{0.60f, 0.56f, 0.50f}}},
               {{14, 14, 178, 21}, {14, 91, 60, 98}, {90, 91, 178, 98}, {14, 14, 21, 98},
                {171, 14, 178, 70}, {120, 14, 126, 50}, {120, 66, 126, 98}},
               {},
               {{30, 28, 44, 42}, {46, 30, 58, 42}, {30, 44, 42, 56}, {96, 26, 112, 40},
                {140, 60, 154, 74}}};
    Roof rc{{11, 11, 126, 101}, {-9, -9, -8, -8}, true, {{40, 24, 70, 34}}, RoofTex::Metal,
            {0.46f, 0.55f, 0.55f}, {}};
    // clang-format on

    ok &= save(dir / "house_a.png", drawWalls(256, 192, a, 21));
    ok &= save(dir / "roof_a.png", drawRoof(256, 192, ra, 31));
    ok &= save(dir / "house_b.png", drawWalls(176, 240, b, 22));
    const Img roof_b = drawRoof(176, 240, rb, 32);
    ok &= save(dir / "roof_b.png", roof_b);
    ok &= save(dir / "house_c.png", drawWalls(192, 112, c, 23));
    const Img roof_c = drawRoof(192, 112, rc, 33);
    ok &= save(dir / "roof_c.png", roof_c);
    ok &= write_specular_art(dir, {water.p, water.w, water.h}, {roof_b.p, roof_b.w, roof_b.h},
                             {roof_c.p, roof_c.w, roof_c.h});

    // Tree crowns.
    ok &= save(dir / "tree_a.png", drawTrees(128, 128, {{60, 60, 44, 41}}));
    ok &= save(dir / "tree_b.png",
               drawTrees(208, 176, {{62, 72, 42, 42}, {134, 62, 36, 43}, {100, 116, 40, 44}}));

    if (!ok) return 1;
    std::printf("wrote example art to %s\n", dir.c_str());
    return 0;
}
