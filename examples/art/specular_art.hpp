#pragma once
// The harbour's masks for acetate.specular (specular_art.cpp): where surfaces shine, how rough
// they are, and which way they face, for the water's edge on the ground and two roofs.

#include <filesystem>
#include <vector>

// An image drawn by make_example_art: premultiplied RGBA floats, row-major, y down.
struct ArtImage {
    const std::vector<float>& rgba;
    int width, height;
};

// Writes ground_{Specular,Roughness,Normal}.png from the ground's water mask (its red channel,
// 1280x720), and roof_b_* and roof_c_* from the slate and metal roofs as drawn (176x240,
// 192x112). Returns false, after printing why, if a file cannot be written.
bool write_specular_art(const std::filesystem::path& dir, const ArtImage& water,
                        const ArtImage& roof_b, const ArtImage& roof_c);
