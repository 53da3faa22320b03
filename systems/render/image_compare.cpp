#include "systems/render/image_compare.hpp"

#include "engine/gpu/png.hpp"

#include <cstdlib>
#include <string_view>

namespace aloha {

ImageDiff compare_images(const gpu::Rgba8Image& a, const gpu::Rgba8Image& b, int per_pixel_threshold) {
    ImageDiff d;
    d.same_size = a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
                  a.pixels.size() == size_t(a.width) * a.height * 4;
    if (!d.same_size) return d;
    const size_t n = size_t(a.width) * a.height;
    for (size_t i = 0; i < n; ++i) {
        int worst = 0;
        for (size_t c = 0; c < 4; ++c) {
            const int diff = std::abs(int(a.pixels[i * 4 + c]) - int(b.pixels[i * 4 + c]));
            worst = diff > worst ? diff : worst;
        }
        if (worst > per_pixel_threshold) ++d.differing_pixels;
        if (worst > d.max_channel_diff) d.max_channel_diff = worst;
    }
    d.differing_fraction = n ? double(d.differing_pixels) / double(n) : 0.0;
    return d;
}

Status check_golden(const gpu::Rgba8Image& actual, const std::string& golden_path, const GoldenOptions& options) {
    const char* update = std::getenv("ALOHA_UPDATE_GOLDEN");
    if (update != nullptr && std::string_view(update) == "1")
        return gpu::write_png(golden_path, actual.width, actual.height, actual.pixels);
    Result<gpu::Rgba8Image> golden = gpu::read_png(golden_path);
    if (!golden) {
        Error e = golden.error();
        e.message += " (set ALOHA_UPDATE_GOLDEN=1 to write the golden image from this run)";
        return e;
    }
    const ImageDiff d = compare_images(actual, golden.value(), options.per_pixel_threshold);
    std::string problem;
    if (!d.same_size) {
        problem = "size " + std::to_string(actual.width) + "x" + std::to_string(actual.height) +
                  " differs from golden " + std::to_string(golden.value().width) + "x" +
                  std::to_string(golden.value().height);
    } else if (d.differing_fraction > options.max_fraction) {
        problem = std::to_string(d.differing_pixels) + " pixels (" + std::to_string(d.differing_fraction * 100.0) +
                  "%) differ by more than " + std::to_string(options.per_pixel_threshold) +
                  " LSB (allowed " + std::to_string(options.max_fraction * 100.0) +
                  "%); largest channel difference " + std::to_string(d.max_channel_diff);
    }
    if (problem.empty()) return {};
    if (!options.actual_dump_path.empty()) {
        (void)gpu::write_png(options.actual_dump_path, actual.width, actual.height, actual.pixels);
        problem += "; this run's image: " + options.actual_dump_path;
    }
    return make_error(golden_path, problem);
}

}  // namespace aloha
