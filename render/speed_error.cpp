#include "render/speed_error.h"

#include "core/atomic_file.h"
#include "core/errors.h"
#include "core/random.h"
#include "render/baseline_renderers.h"
#include "render/metrics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

namespace lh {

std::vector<Vec3d> freeSpacePoints(const RenderVolume& volume, int count, uint64_t seed) {
    if (volume.levels.empty()) throw InputError("volume has no levels");
    const RenderLevel& level = volume.levels[std::min<std::size_t>(1, volume.levels.size() - 1)];
    Random rng(seed);
    std::vector<Vec3d> points;
    for (int tries = 0; tries < 100000 && int(points.size()) < count; ++tries) {
        Vec3d q;
        for (int a = 0; a < 3; ++a) q[a] = rng.uniform(level.domainLo[a], level.domainHi[a]);
        const Vec3d p = level.indexToWorld * (q - level.indexOffset);
        if (volume.sampleWorld(p).sigma == 0.f) points.push_back(p);
    }
    if (int(points.size()) < count) throw InputError("the volume has no empty space to put query points in");
    return points;
}

std::vector<SpeedErrorRow> measureSpeedAgainstError(const LightingVolume& volume, const SpeedErrorOptions& o,
                                                    const std::function<void(const std::string&)>& progress) {
    const RenderVolume prepared(volume);
    const std::vector<Vec3d> points = freeSpacePoints(prepared, o.points, o.seed);
    const auto say = [&](const std::string& s) { if (progress) progress(s); };
    say("reference envmaps (0.05-voxel steps, no skipping)");
    std::vector<ImageRGB> reference;
    for (const Vec3d& p : points) reference.push_back(renderEnvmap(prepared, p, {o.width, o.height, MarchOptions::reference()}));

    std::vector<SpeedErrorRow> rows;
    const auto measure = [&](const std::string& method, const std::string& setting,
                             const std::function<ImageRGB(const Vec3d&)>& render) {
        say(method + ", " + setting);
        std::vector<ImageRGB> images;
        const auto start = std::chrono::steady_clock::now();
        for (const Vec3d& p : points) images.push_back(render(p));
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        double squared = 0, mean = 0, psnrSum = 0;
        std::size_t n = 0;
        for (std::size_t i = 0; i < points.size(); ++i) {
            for (std::size_t k = 0; k < images[i].pixels.size(); ++k) {
                squared += std::pow(double(images[i].pixels[k]) - reference[i].pixels[k], 2);
                mean += reference[i].pixels[k];
                ++n;
            }
            psnrSum += std::min(psnr(images[i], reference[i]), 100.0);  // identical -> capped
        }
        rows.push_back({method, setting, ms / points.size(), std::sqrt(squared / n) / (mean / n), psnrSum / points.size()});
    };
    for (double threshold : {1e-4, 1e-2})
        for (double step : {0.25, 0.5, 1.0, 2.0}) {
            std::ostringstream s;
            s << "step " << step << ", T<" << threshold;
            measure("ours", s.str(), [&](const Vec3d& p) {
                return renderEnvmap(prepared, p, {o.width, o.height, MarchOptions{step, threshold, true}});
            });
        }
    for (double step : {0.5, 1.0, 2.0})
        measure("openvdb-fixed-step", "step " + std::to_string(step).substr(0, 4),
                [&](const Vec3d& p) { return renderEnvmapOpenVdbFixedStep(volume, p, o.width, o.height, step); });
    for (int spheres : {32, 64, 128, 256})
        measure("paper-spheres", std::to_string(spheres) + " spheres/level",
                [&](const Vec3d& p) { return renderEnvmapConcentricSpheres(prepared, p, o.width, o.height, spheres); });
    return rows;
}

namespace {

std::string svgPlot(const std::vector<SpeedErrorRow>& rows) {
    // Log-log axes: x = ms per envmap, y = relative RMSE.
    double x0 = 1e30, x1 = 0, y0 = 1e30, y1 = 0;
    for (const auto& r : rows) {
        x0 = std::min(x0, r.msPerEnvmap), x1 = std::max(x1, r.msPerEnvmap);
        const double e = std::max(r.relativeRmse, 1e-6);
        y0 = std::min(y0, e), y1 = std::max(y1, e);
    }
    x0 = std::pow(10, std::floor(std::log10(x0))), x1 = std::pow(10, std::ceil(std::log10(x1)));
    y0 = std::pow(10, std::floor(std::log10(y0))), y1 = std::pow(10, std::ceil(std::log10(y1)));
    const double W = 640, H = 420, L = 70, R = 180, T = 20, B = 50;
    const auto px = [&](double x) { return L + (std::log10(x) - std::log10(x0)) / (std::log10(x1) - std::log10(x0)) * (W - L - R); };
    const auto py = [&](double y) { return T + (std::log10(y1) - std::log10(std::max(y, 1e-6))) / (std::log10(y1) - std::log10(y0)) * (H - T - B); };
    std::ostringstream s;
    s << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' font-family='sans-serif' font-size='12'>\n"
      << "<rect width='100%' height='100%' fill='white'/>\n";
    for (double x = x0; x <= x1 * 1.001; x *= 10)
        s << "<line x1='" << px(x) << "' y1='" << T << "' x2='" << px(x) << "' y2='" << H - B << "' stroke='#ddd'/>"
          << "<text x='" << px(x) << "' y='" << H - B + 16 << "' text-anchor='middle'>" << x << "</text>\n";
    for (double y = y0; y <= y1 * 1.001; y *= 10)
        s << "<line x1='" << L << "' y1='" << py(y) << "' x2='" << W - R << "' y2='" << py(y) << "' stroke='#ddd'/>"
          << "<text x='" << L - 6 << "' y='" << py(y) + 4 << "' text-anchor='end'>" << y << "</text>\n";
    s << "<text x='" << (L + W - R) / 2 << "' y='" << H - 12 << "' text-anchor='middle'>ms per 240x120 envmap (2 cores)</text>\n"
      << "<text x='16' y='" << (T + H - B) / 2 << "' transform='rotate(-90 16 " << (T + H - B) / 2
      << ")' text-anchor='middle'>RMSE / mean radiance</text>\n";
    const std::map<std::string, std::string> colours = {{"ours", "#d62728"}, {"openvdb-fixed-step", "#1f77b4"}, {"paper-spheres", "#2ca02c"}};
    int legend = 0;
    for (const auto& [method, colour] : colours) {
        std::vector<SpeedErrorRow> mine;
        for (const auto& r : rows)
            if (r.method == method) mine.push_back(r);
        if (mine.empty()) continue;
        std::sort(mine.begin(), mine.end(), [](const auto& a, const auto& b) { return a.msPerEnvmap < b.msPerEnvmap; });
        for (const auto& r : mine)
            s << "<circle cx='" << px(r.msPerEnvmap) << "' cy='" << py(r.relativeRmse) << "' r='4' fill='" << colour
              << "'><title>" << r.method << ": " << r.setting << "</title></circle>\n";
        s << "<text x='" << W - R + 12 << "' y='" << T + 20 + 18 * legend++ << "' fill='" << colour << "'>" << method << "</text>\n";
    }
    s << "</svg>\n";
    return s.str();
}

}  // namespace

void writeSpeedErrorReport(const std::vector<SpeedErrorRow>& rows, const std::string& directory) {
    std::filesystem::create_directories(directory);
    std::ostringstream csv, md;
    csv << "method,setting,ms_per_envmap,envmaps_per_second,relative_rmse,psnr_db\n";
    md << "| method | setting | ms / envmap | envmaps / s | RMSE / mean radiance | PSNR (dB) |\n|---|---|---|---|---|---|\n";
    for (const auto& r : rows) {
        csv << r.method << "," << r.setting << "," << r.msPerEnvmap << "," << 1000 / r.msPerEnvmap << ","
            << r.relativeRmse << "," << r.psnr << "\n";
        char line[256];
        std::snprintf(line, sizeof line, "| %s | %s | %.1f | %.1f | %.2e | %.1f |\n", r.method.c_str(),
                      r.setting.c_str(), r.msPerEnvmap, 1000 / r.msPerEnvmap, r.relativeRmse, r.psnr);
        md << line;
    }
    const std::filesystem::path dir(directory);
    writeTextFile((dir / "speed_error.csv").string(), csv.str());
    writeTextFile((dir / "speed_error.md").string(), md.str());
    writeTextFile((dir / "speed_error.svg").string(), svgPlot(rows));
}

}  // namespace lh
