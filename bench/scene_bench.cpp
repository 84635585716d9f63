// Composing and compiling scenes (the scene room): the three scenes mjarm builds most.
//
// Protocol (also in every benchmark's label):
// - Cases, one iteration = one whole scene:
//     PickTableFile/compose    load_scene_file(models/scenes/pick_table.yaml): panda + franka_hand,
//                              arena with table, 2 objects, a fixture, site, camera, 4 sensors,
//                              a weld, an edit; no compile
//     PickTableFile/compile    Scene::compile() of that scene (keyframes combined)
//     DockingScene/compose     docking_scene(): iiwa14_torque + docking_peg, arena, the compound
//                              socket (34 pieces), 2 sensors, 75 edits by name; no compile
//     DockingScene/compile     Scene::compile() of that scene
//     PickPlaceScene/build     build_pick_place_scene() with default options (arm6): compose,
//                              edits, compile and the name look-ups of a trial
// - The files are read from the source tree's models/ (page cache warm after the first run).
// Run: build/bench_scene [--benchmark_min_time=0.5]; docs/scene.md keeps the figures.

#include <benchmark/benchmark.h>

#include <filesystem>

#include "mjarm/scene/scene.hpp"
#include "mjarm/scene/scene_file.hpp"
#include "mjarm/tasks/docking/scene.hpp"
#include "mjarm/tasks/pick_place/scene.hpp"

namespace {

const std::filesystem::path kPickTable =
    std::filesystem::path(MJARM_MODELS_DIR) / "scenes" / "pick_table.yaml";

void BM_PickTableFileCompose(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(mjarm::load_scene_file(kPickTable));
  state.SetLabel("load_scene_file(pick_table.yaml), no compile");
}
BENCHMARK(BM_PickTableFileCompose)->Unit(benchmark::kMillisecond);

void BM_PickTableFileCompile(benchmark::State& state) {
  const mjarm::Scene scene = mjarm::load_scene_file(kPickTable);
  for (auto _ : state) benchmark::DoNotOptimize(scene.compile());
  state.SetLabel("Scene::compile of pick_table.yaml");
}
BENCHMARK(BM_PickTableFileCompile)->Unit(benchmark::kMillisecond);

void BM_DockingSceneCompose(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(mjarm::docking_scene());
  state.SetLabel("docking_scene(): iiwa14 + peg + compound socket, edits; no compile");
}
BENCHMARK(BM_DockingSceneCompose)->Unit(benchmark::kMillisecond);

void BM_DockingSceneCompile(benchmark::State& state) {
  const mjarm::Scene scene = mjarm::docking_scene();
  for (auto _ : state) benchmark::DoNotOptimize(scene.compile());
  state.SetLabel("Scene::compile of the docking scene");
}
BENCHMARK(BM_DockingSceneCompile)->Unit(benchmark::kMillisecond);

void BM_PickPlaceSceneBuild(benchmark::State& state) {
  const mjarm::PickPlaceSceneOptions options;
  for (auto _ : state) benchmark::DoNotOptimize(mjarm::build_pick_place_scene(options));
  state.SetLabel("build_pick_place_scene(arm6, defaults): compose + compile");
}
BENCHMARK(BM_PickPlaceSceneBuild)->Unit(benchmark::kMillisecond);

}  // namespace
