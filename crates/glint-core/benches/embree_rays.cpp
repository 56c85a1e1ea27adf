// The anchor of `glint bench rays`: Intel Embree 3 casting the same rays at the same triangles,
// on the same machine, so glint's figures can be quoted as ratios measured in one session
// (the machine's speed drifts by 1.3-1.5x between sessions). Not part of the build: it needs
// Embree 3 (Debian: libembree-dev) and a C++17 compiler.
//
//   glint bench rays bumpy --threads 2 --export DIR
//   g++ -O2 -std=c++17 crates/glint-core/benches/embree_rays.cpp -lembree3 -pthread -o embree_rays
//   ./embree_rays DIR [THREADS] [RUNS]
//
// Prints the build time and, per ray set, the median and best of RUNS timed runs after one
// warm-up (as glint does), Mrays/s from the median, the hit fraction, and how many rays hit
// another triangle than glint's CPU tracer did (with the largest relative difference of t where
// they agree). The file formats are described in src/cli/bench_export.rs. Rays are cast one by
// one (rtcIntersect1) by THREADS threads taking 256 rays at a time, as glint's CPU does.

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

namespace {

struct RayRecord {
    float origin_t_min[4];
    float dir_t_max[4];
};

struct HitRecord {
    uint32_t prim;
    uint32_t index;
    float t;
    uint32_t pad;
};

// glint's kind of a triangle hit and of a miss (cpu::intersect::Prim, rays::PRIM_NONE).
constexpr uint32_t PRIM_TRIANGLE = 3;
constexpr uint32_t PRIM_NONE = 0;
constexpr size_t RAYS_PER_TASK = 256;

[[noreturn]] void fail(const std::string& message) {
    std::fprintf(stderr, "embree_rays: %s\n", message.c_str());
    std::exit(1);
}

// The whole of `path` as items of T; an error names the file if it cannot be read or is not a
// whole number of items.
template <typename T>
std::vector<T> read_array(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) fail("cannot read " + path + " (made by `glint bench rays --export DIR`)");
    const auto bytes = static_cast<size_t>(in.tellg());
    if (bytes % sizeof(T) != 0) fail(path + ": " + std::to_string(bytes) + " bytes is not a whole number of records");
    std::vector<T> items(bytes / sizeof(T));
    in.seekg(0);
    in.read(reinterpret_cast<char*>(items.data()), static_cast<std::streamsize>(bytes));
    if (!in) fail("cannot read all of " + path);
    return items;
}

double ms_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

struct Timing {
    double median_ms;
    double best_ms;
};

Timing summarise(std::vector<double> times) {
    std::sort(times.begin(), times.end());
    return {times[times.size() / 2], times.front()};
}

void on_error(void*, RTCError code, const char* message) {
    fail("Embree error " + std::to_string(static_cast<int>(code)) + ": " + (message ? message : ""));
}

RTCScene build_scene(RTCDevice device, std::vector<float>& vertices, std::vector<uint32_t>& indices) {
    RTCScene scene = rtcNewScene(device);
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    // glint stores positions as (x, y, z, 1): a 16-byte stride, which also gives Embree the
    // readable bytes past the last vertex it asks for.
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, vertices.data(), 0,
                               4 * sizeof(float), vertices.size() / 4);
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, indices.data(), 0,
                               3 * sizeof(uint32_t), indices.size() / 3);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    rtcCommitScene(scene);
    return scene;
}

// Every ray's closest hit, cast by `threads` threads in tasks of RAYS_PER_TASK rays.
void cast(RTCScene scene, const std::vector<RayRecord>& rays, std::vector<HitRecord>& hits, unsigned threads) {
    std::atomic<size_t> next{0};
    auto worker = [&] {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        for (;;) {
            const size_t start = next.fetch_add(RAYS_PER_TASK);
            if (start >= rays.size()) return;
            const size_t end = std::min(start + RAYS_PER_TASK, rays.size());
            for (size_t i = start; i < end; ++i) {
                const RayRecord& r = rays[i];
                RTCRayHit rh;
                rh.ray.org_x = r.origin_t_min[0];
                rh.ray.org_y = r.origin_t_min[1];
                rh.ray.org_z = r.origin_t_min[2];
                rh.ray.tnear = r.origin_t_min[3];
                rh.ray.dir_x = r.dir_t_max[0];
                rh.ray.dir_y = r.dir_t_max[1];
                rh.ray.dir_z = r.dir_t_max[2];
                rh.ray.time = 0.0f;
                rh.ray.tfar = r.dir_t_max[3];
                rh.ray.mask = ~0u;
                rh.ray.id = 0;
                rh.ray.flags = 0;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
                rtcIntersect1(scene, &context, &rh);
                hits[i] = rh.hit.geomID == RTC_INVALID_GEOMETRY_ID
                              ? HitRecord{PRIM_NONE, 0, 0.0f, 0}
                              : HitRecord{PRIM_TRIANGLE, rh.hit.primID, rh.ray.tfar, 0};
            }
        }
    };
    std::vector<std::thread> pool;
    for (unsigned k = 1; k < threads; ++k) pool.emplace_back(worker);
    worker();
    for (auto& t : pool) t.join();
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || argc > 4) fail("usage: embree_rays DIR [THREADS (default 2)] [RUNS (default 5)]");
    const std::string dir = argv[1];
    const long threads = argc > 2 ? std::strtol(argv[2], nullptr, 10) : 2;
    const long runs = argc > 3 ? std::strtol(argv[3], nullptr, 10) : 5;
    if (threads < 1 || threads > 1024) fail("THREADS must be in [1, 1024]");
    if (runs < 1 || runs > 100) fail("RUNS must be in [1, 100]");

    auto vertices = read_array<float>(dir + "/vertices.f32x4");
    auto indices = read_array<uint32_t>(dir + "/triangles.u32x3");
    if (vertices.size() % 4 != 0 || indices.size() % 3 != 0) fail(dir + ": vertex or triangle file cut short");
    const size_t vertex_count = vertices.size() / 4;
    for (uint32_t v : indices)
        if (v >= vertex_count) fail(dir + "/triangles.u32x3: an index past the " + std::to_string(vertex_count) + " vertices");

    const std::string config = "threads=" + std::to_string(threads);
    RTCDevice device = rtcNewDevice(config.c_str());
    if (!device) fail("cannot open an Embree device (" + config + ")");
    rtcSetDeviceErrorFunction(device, on_error, nullptr);

    // The build: one warm-up, then RUNS timed, each a new scene.
    std::vector<double> build_times;
    RTCScene scene = nullptr;
    for (long run = 0; run <= runs; ++run) {
        if (scene) rtcReleaseScene(scene);
        const auto start = std::chrono::steady_clock::now();
        scene = build_scene(device, vertices, indices);
        if (run > 0) build_times.push_back(ms_since(start));
    }
    const Timing build = summarise(build_times);
    const size_t triangles = indices.size() / 3;
    std::printf("Embree %d.%d.%d: %zu triangles; %ld threads\n", RTC_VERSION_MAJOR, RTC_VERSION_MINOR,
                RTC_VERSION_PATCH, triangles, threads);
    std::printf("  warm-up, then median and best of %ld runs; Mrays/s and Mtris/s from the median\n", runs);
    std::printf("  BVH build    %10.1f ms median %10.1f ms best %9.2f Mtris/s\n", build.median_ms, build.best_ms,
                triangles / (build.median_ms * 1e3));
    std::printf("  %-11s %-8s %10s %12s %12s %9s %8s\n", "rays", "backend", "count", "median ms", "best ms", "Mrays/s",
                "hit %");

    for (const char* set : {"primary", "incoherent"}) {
        const auto rays = read_array<RayRecord>(dir + "/" + set + ".rays");
        const auto glint_hits = read_array<HitRecord>(dir + "/" + set + ".hits");
        if (glint_hits.size() != rays.size()) fail(std::string(set) + ": the hit and ray files differ in length");
        std::vector<HitRecord> hits(rays.size());
        std::vector<double> times;
        for (long run = 0; run <= runs; ++run) {
            const auto start = std::chrono::steady_clock::now();
            cast(scene, rays, hits, static_cast<unsigned>(threads));
            if (run > 0) times.push_back(ms_since(start));
        }
        const Timing t = summarise(times);
        size_t hit = 0, differing = 0;
        double max_rel = 0.0;
        for (size_t i = 0; i < rays.size(); ++i) {
            const HitRecord& a = hits[i];
            const HitRecord& b = glint_hits[i];
            hit += a.prim != PRIM_NONE;
            if (a.prim != b.prim || (a.prim != PRIM_NONE && a.index != b.index)) {
                ++differing;
            } else if (a.prim != PRIM_NONE) {
                const double scale = std::max(std::fabs(static_cast<double>(b.t)), 1e-30);
                max_rel = std::max(max_rel, std::fabs(static_cast<double>(a.t) - b.t) / scale);
            }
        }
        std::printf("  %-11s %-8s %10zu %12.1f %12.1f %9.2f %8.2f\n", set, "embree", rays.size(), t.median_ms, t.best_ms,
                    rays.size() / (t.median_ms * 1e3), 100.0 * hit / rays.size());
        std::printf("  embree vs glint cpu, %s: %zu of %zu rays hit another primitive (%.4f %%), max relative t "
                    "difference %.2e\n",
                    set, differing, rays.size(), 100.0 * differing / rays.size(), max_rel);
    }
    rtcReleaseScene(scene);
    rtcReleaseDevice(device);
    return 0;
}
