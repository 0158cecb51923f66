// The `soak bench` world in Jolt Physics, for a side-by-side timing:
// N bodies on a square grid 2 m apart, floating on calm water (y = 0) at
// their draft, half of them 1 × 0.6 × 0.8 m boxes and half spheres of
// radius 0.5 m (or every one a sphere), density 500 kg/m³ in water of
// 1000 kg/m³, dt = 1/60 s, no contacts. Each step applies Jolt's own
// buoyancy and drag (`Body::ApplyBuoyancyImpulse`: the exact submerged
// volume of the convex shape under the plane, a quadratic drag on the
// submerged part) to every body the water's box meets, as Jolt's water
// samples do, then steps the world. Bodies never sleep (soak's don't).
//
// The spheres are convex hulls of the vertices of the mesh `soak bench`
// bakes (`builtin::sphere(0.5, 64, 32)`), as many as Jolt keeps in a hull
// (256), or Jolt's analytic sphere with `--analytic`.
//
// Build and run: `scripts/jolt_bench.sh JOLT_CHECKOUT [N] [THREADS]`.
// Prints one line: the median and mean step time over the timed steps.

#include <Jolt/Jolt.h>

#include <Jolt/Core/Factory.h>
#include <Jolt/Core/JobSystemSingleThreaded.h>
#include <Jolt/Core/JobSystemThreadPool.h>
#include <Jolt/Core/TempAllocator.h>
#include <Jolt/Physics/Body/BodyCreationSettings.h>
#include <Jolt/Physics/Body/BodyLock.h>
#include <Jolt/Physics/Collision/BroadPhase/BroadPhaseQuery.h>
#include <Jolt/Physics/Collision/CollideShape.h>
#include <Jolt/Physics/Collision/Shape/BoxShape.h>
#include <Jolt/Physics/Collision/Shape/ConvexHullShape.h>
#include <Jolt/Physics/Collision/Shape/SphereShape.h>
#include <Jolt/Physics/PhysicsSettings.h>
#include <Jolt/Physics/PhysicsSystem.h>
#include <Jolt/RegisterTypes.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <vector>

using namespace JPH;

namespace {

constexpr ObjectLayer MOVING = 0;
constexpr BroadPhaseLayer MOVING_BP(0);

class OneLayer final : public BroadPhaseLayerInterface {
public:
    uint GetNumBroadPhaseLayers() const override { return 1; }
    BroadPhaseLayer GetBroadPhaseLayer(ObjectLayer) const override { return MOVING_BP; }
#if defined(JPH_EXTERNAL_PROFILE) || defined(JPH_PROFILE_ENABLED)
    const char *GetBroadPhaseLayerName(BroadPhaseLayer) const override { return "moving"; }
#endif
};

class AllPairs final : public ObjectVsBroadPhaseLayerFilter {
public:
    bool ShouldCollide(ObjectLayer, BroadPhaseLayer) const override { return true; }
};

class AllObjects final : public ObjectLayerPairFilter {
public:
    bool ShouldCollide(ObjectLayer, ObjectLayer) const override { return true; }
};

// Applies buoyancy and drag to each body the water's box meets.
class Floater final : public CollideShapeBodyCollector {
public:
    Floater(PhysicsSystem &system, float dt) : system(system), dt(dt) {}
    void AddHit(const BodyID &id) override {
        BodyLockWrite lock(system.GetBodyLockInterface(), id);
        if (!lock.Succeeded()) {
            return;
        }
        Body &body = lock.GetBody();
        // Fluid twice as dense as the body; Jolt's suggested drag factors.
        body.ApplyBuoyancyImpulse(RVec3::sZero(), Vec3::sAxisY(), 2.0f, 0.5f, 0.01f, Vec3::sZero(),
                                  system.GetGravity(), dt);
    }

private:
    PhysicsSystem &system;
    float dt;
};

// The vertices of a UV sphere of `segments` around and `rings` from pole
// to pole, as soak's `builtin::sphere` lays them out.
std::vector<Vec3> sphere_points(float radius, int segments, int rings) {
    std::vector<Vec3> points;
    points.push_back(Vec3(0, radius, 0));
    for (int r = 1; r < rings; ++r) {
        const float theta = float(M_PI) * float(r) / float(rings);
        for (int s = 0; s < segments; ++s) {
            const float phi = 2.0f * float(M_PI) * float(s) / float(segments);
            points.push_back(radius * Vec3(std::sin(theta) * std::cos(phi), std::cos(theta),
                                           std::sin(theta) * std::sin(phi)));
        }
    }
    points.push_back(Vec3(0, -radius, 0));
    return points;
}

}  // namespace

int main(int argc, char **argv) {
    int n = 1000;
    int threads = 1;
    bool analytic = false;
    bool spheres_only = false;
    int timed = 300;
    for (int i = 1; i < argc; ++i) {
        if (std::strcmp(argv[i], "--analytic") == 0) {
            analytic = true;
        } else if (std::strcmp(argv[i], "--spheres") == 0) {
            spheres_only = true;
        } else if (std::strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
            threads = std::atoi(argv[++i]);
        } else if (std::strcmp(argv[i], "--steps") == 0 && i + 1 < argc) {
            timed = std::atoi(argv[++i]);
        } else {
            n = std::atoi(argv[i]);
        }
    }
    if (n <= 0 || threads <= 0 || timed <= 0) {
        std::fprintf(stderr, "usage: jolt_floating [N] [--threads T] [--steps S] [--spheres] [--analytic]\n");
        return 2;
    }

    RegisterDefaultAllocator();
    Factory::sInstance = new Factory();
    RegisterTypes();
    TempAllocatorImpl temp(64 * 1024 * 1024);
    std::unique_ptr<JobSystem> jobs;
    if (threads == 1) {
        jobs = std::make_unique<JobSystemSingleThreaded>(cMaxPhysicsJobs);
    } else {
        // The calling thread works on the jobs as well.
        jobs = std::make_unique<JobSystemThreadPool>(cMaxPhysicsJobs, cMaxPhysicsBarriers, threads - 1);
    }

    OneLayer layers;
    AllPairs object_vs_broadphase;
    AllObjects object_pairs;
    PhysicsSystem system;
    system.Init(uint(n) + 16, 0, 65536, 10240, layers, object_vs_broadphase, object_pairs);

    const float density = 500.0f;
    Ref<BoxShape> box = new BoxShape(Vec3(0.5f, 0.3f, 0.4f), 0.0f);
    box->SetDensity(density);
    Ref<Shape> sphere;
    if (analytic) {
        Ref<SphereShape> ball = new SphereShape(0.5f);
        ball->SetDensity(density);
        sphere = ball;
    } else {
        const std::vector<Vec3> points = sphere_points(0.5f, 64, 32);
        ConvexHullShapeSettings hull(points.data(), int(points.size()), 0.0f);
        hull.SetDensity(density);
        ShapeSettings::ShapeResult made = hull.Create();
        if (made.HasError()) {
            std::fprintf(stderr, "hull: %s\n", made.GetError().c_str());
            return 1;
        }
        sphere = made.Get();
        std::fprintf(stderr, "hull sphere: %u points of %zu\n",
                     static_cast<const ConvexHullShape *>(sphere.GetPtr())->GetNumPoints(), points.size());
    }

    BodyInterface &bodies = system.GetBodyInterfaceNoLock();
    const int side = int(std::ceil(std::sqrt(double(n))));
    for (int i = 0; i < n; ++i) {
        const float x = 2.0f * float(i % side - side / 2);
        const float z = 2.0f * float(i / side - side / 2);
        const bool is_box = !spheres_only && i % 2 == 0;
        BodyCreationSettings settings(is_box ? box : sphere, RVec3(x, 0.0f, z), Quat::sIdentity(),
                                      EMotionType::Dynamic, MOVING);
        settings.mAllowSleeping = false;
        bodies.CreateAndAddBody(settings, EActivation::Activate);
    }
    system.OptimizeBroadPhase();

    const float dt = 1.0f / 60.0f;
    AABox water(Vec3(-1.0e4f, -1.0e4f, -1.0e4f), Vec3(1.0e4f, 0.0f, 1.0e4f));
    auto step = [&] {
        Floater floater(system, dt);
        system.GetBroadPhaseQuery().CollideAABox(water, floater);
        system.Update(dt, 1, &temp, jobs.get());
    };
    for (int i = 0; i < 10; ++i) {
        step();
    }
    std::vector<double> ms;
    for (int i = 0; i < timed; ++i) {
        const auto t0 = std::chrono::steady_clock::now();
        step();
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    double mean = 0.0;
    for (double m : ms) {
        mean += m;
    }
    mean /= double(ms.size());
    std::sort(ms.begin(), ms.end());
    // Where a body floats after the run: half under water at rest.
    float lowest = 1e9f, highest = -1e9f;
    BodyIDVector ids;
    system.GetBodies(ids);
    for (const BodyID &id : ids) {
        const float y = float(bodies.GetCenterOfMassPosition(id).GetY());
        lowest = std::min(lowest, y);
        highest = std::max(highest, y);
    }
    std::printf("jolt %d bodies (%s), %d thread%s: %.3f ms per step (median of %d; mean %.3f ms); centres at y %.3f to %.3f m\n",
                n, spheres_only ? (analytic ? "analytic spheres" : "hull spheres")
                                : (analytic ? "boxes and analytic spheres" : "boxes and hull spheres"),
                threads, threads == 1 ? "" : "s", ms[ms.size() / 2], timed, mean, lowest, highest);

    UnregisterTypes();
    delete Factory::sInstance;
    Factory::sInstance = nullptr;
    return 0;
}
