// Where settling's time goes (issue 46; docs/benchmarks.md "Settling"). Samples FILE with
// --settle on one thread, as `prs sample FILE --settle -n N -s S --threads 1` does, and splits
// the time of every settling: building the physics model (the export, its MJCF, MuJoCo's
// compiler, mjData), stepping (with MuJoCo's own timers: collision, constraint solver, rest),
// and the checks after; and the share spent on settlings that were rejected.
//   ./build/bench/settle_profile examples/bin_pile.prs [-n 20] [-s 1]
// Each settling is run twice, the second time instrumented (the rest of the program never sees
// the second run), so the bench takes about twice `prs sample`'s time.
#include <fmt/format.h>

#include <chrono>
#include <algorithm>
#include <cstdlib>
#include <vector>
#include <string>

#include "export/export.h"
#include "sampling/sampler.h"
#include "sim/mujoco_model.h"
#include "sim/settle.h"

namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

mjtNum NowInMicroseconds() {
  return std::chrono::duration<double, std::micro>(Clock::now().time_since_epoch()).count();
}

struct Split {
  int settlings = 0, rejected = 0;
  double total_s = 0, rejected_s = 0;
  double export_s = 0, compile_s = 0, data_s = 0;
  double step_s = 0, collision_s = 0, constraint_s = 0;
  double simulated_s = 0;
  long steps = 0;
  int max_stack = 0, max_con = 0, max_efc = 0, nstack = 0;
};

// The instrumented copy of one settling: the same model, stepped as long as the real one was.
void Profile(const prs::lang::Scene& drawn, double settled_s, double step_s, Split& split) {
  auto start = Clock::now();
  const prs::exporting::ExportScene model = prs::exporting::MakeExportScene(drawn, "settle");
  prs::exporting::ExportScene settled_model = model;
  settled_model.settled = true;
  settled_model.contacts_per_free_body = 8;  // as sim/stability.cc first tries
  const std::string xml = prs::exporting::WriteScene(settled_model, prs::exporting::Format::kMjcf);
  split.export_s += SecondsSince(start);
  start = Clock::now();
  prs::sim::ModelPtr m = prs::sim::LoadModelFromXml(xml);
  m->opt.timestep = step_s;
  split.compile_s += SecondsSince(start);
  start = Clock::now();
  prs::sim::DataPtr d = prs::sim::MakeData(*m);
  split.data_s += SecondsSince(start);
  const long steps = std::lround(settled_s / m->opt.timestep);
  for (long k = 0; k < steps; ++k) mj_step(m.get(), d.get());
  split.step_s += d->timer[mjTIMER_STEP].duration * 1e-6;
  split.collision_s += d->timer[mjTIMER_POS_COLLISION].duration * 1e-6;
  split.constraint_s += d->timer[mjTIMER_CONSTRAINT].duration * 1e-6;
  split.simulated_s += settled_s;
  split.max_stack = std::max(split.max_stack, d->maxuse_stack);
  split.max_con = std::max(split.max_con, d->maxuse_con);
  split.max_efc = std::max(split.max_efc, d->maxuse_efc);
  split.nstack = m->nstack;
  split.steps += steps;
}

// One settling against the same drawn scene settled at the reference step.
struct Reference {
  int both_kept = 0, both_rejected = 0, only_kept = 0, only_reference_kept = 0;
  std::vector<double> move_m;       // per free body kept in both: distance between the two rests
  std::vector<double> settled_ds;   // settled_s minus the reference's
};

void Compare(const prs::lang::Scene& settled, bool rejected, const prs::lang::Scene& fine,
             bool fine_rejected, Reference& reference) {
  if (rejected && fine_rejected) ++reference.both_rejected;
  if (!rejected && fine_rejected) ++reference.only_kept;
  if (rejected && !fine_rejected) ++reference.only_reference_kept;
  if (rejected || fine_rejected) return;
  ++reference.both_kept;
  reference.settled_ds.push_back(settled.settled_s.value_or(0) - fine.settled_s.value_or(0));
  for (size_t i = 0; i < settled.objects.size(); ++i) {
    if (settled.objects[i].p_WO == fine.objects[i].p_WO && fine.objects[i].fixed) continue;
    reference.move_m.push_back((settled.objects[i].p_WO - fine.objects[i].p_WO).norm());
  }
}

double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0;
  std::sort(values.begin(), values.end());
  return values[std::min(values.size() - 1, static_cast<size_t>(q * values.size()))];
}

// The checks of issue 46 on a kept scene, made by MuJoCo directly on its MJCF export: the
// deepest contact; how far any free body moves in 1 s at MuJoCo's default 2 ms step; and, for
// examples/bin_pile.prs, whether every free body's centre is inside the bin.
struct Checked {
  int scenes = 0, outside = 0, moved_past_1cm = 0;
  double deepest_m = 0, most_moved_m = 0;
};

void CheckKept(const prs::lang::Scene& scene, bool bin, double step_s, Checked& checked) {
  const prs::exporting::ExportScene exported = prs::exporting::MakeExportScene(scene, "check");
  const prs::sim::ModelPtr m =
      prs::sim::LoadModelFromXml(prs::exporting::WriteScene(exported, prs::exporting::Format::kMjcf));
  if (step_s > 0) m->opt.timestep = step_s;
  const prs::sim::DataPtr d = prs::sim::MakeData(*m);
  mj_forward(m.get(), d.get());
  ++checked.scenes;
  for (int c = 0; c < d->ncon; ++c) {
    checked.deepest_m = std::max(checked.deepest_m, -d->contact[c].dist);
    if (std::getenv("SETTLE_PROFILE_VERBOSE") && -d->contact[c].dist > 0.008) {
      fmt::print("  scene {}: {} into {} {:.1f} mm\n", checked.scenes - 1,
                 mj_id2name(m.get(), mjOBJ_GEOM, d->contact[c].geom1),
                 mj_id2name(m.get(), mjOBJ_GEOM, d->contact[c].geom2), -1e3 * d->contact[c].dist);
    }
  }
  std::vector<Eigen::Vector3d> start;
  for (int b = 0; b < m->nbody; ++b) start.emplace_back(d->xpos + 3 * b);
  while (d->time < 1.0) mj_step(m.get(), d.get());
  double most_moved_m = 0;
  for (int b = 1; b < m->nbody; ++b) {
    most_moved_m = std::max(most_moved_m, (Eigen::Vector3d(d->xpos + 3 * b) - start[b]).norm());
  }
  checked.most_moved_m = std::max(checked.most_moved_m, most_moved_m);
  if (std::getenv("SETTLE_PROFILE_VERBOSE")) {
    for (int b = 1; b < m->nbody; ++b) {
      const double moved = (Eigen::Vector3d(d->xpos + 3 * b) - start[b]).norm();
      if (moved > 0.01) fmt::print("  scene {}: {} moved {:.1f} mm\n", checked.scenes - 1, mj_id2name(m.get(), mjOBJ_BODY, b), 1e3 * moved);
    }
  }
  checked.moved_past_1cm += most_moved_m > 0.01;
  if (!bin) return;
  bool outside = false;
  for (const prs::exporting::Body& body : exported.bodies) {
    if (!body.is_free()) continue;
    const Eigen::Vector3d& p = body.p_WO;
    outside |= !(std::abs(p.x()) < 0.25 && std::abs(p.y()) < 0.2 && p.z() > 0.82 && p.z() < 1.02);
  }
  checked.outside += outside;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: settle_profile FILE [-n N] [-s SEED] [--settle T]\n");
    return 2;
  }
  const std::string file = argv[1];
  int n = 20;
  uint64_t seed = 1;
  prs::sim::SettleOptions settle_options;
  double reference_step_s = 0, check_step_s = 0;
  bool check = false;
  for (int i = 2; i < argc; ++i) {
    const std::string flag = argv[i];
    const char* value = i + 1 < argc ? argv[i + 1] : "0";
    if (flag == "--check") {
      check = true;
      continue;
    }
    if (flag == "-n") n = std::atoi(value);
    else if (flag == "-s") seed = std::strtoull(value, nullptr, 10);
    else if (flag == "--settle") settle_options.duration_s = std::atof(value);
    else if (flag == "--timestep") settle_options.timestep_s = std::atof(value);
    else if (flag == "--reference") reference_step_s = std::atof(value);
    else if (flag == "--check-step") check_step_s = std::atof(value);
    ++i;
  }
  mjcb_time = NowInMicroseconds;
  prs::lang::DiagnosticEngine diagnostics;
  prs::lang::CompileOptions compile;
  auto program = prs::lang::CompileFile(file, compile, diagnostics);
  if (diagnostics.has_errors()) {
    std::fprintf(stderr, "%s does not compile\n", file.c_str());
    return 1;
  }
  Split split;
  const auto settle = prs::sim::MakeSettleTest(settle_options);
  Reference reference;
  double reference_s = 0;  // not counted in the wall time
  std::vector<prs::lang::Scene> kept;
  prs::sampling::SampleOptions options;
  options.max_attempts = 10'000'000;
  options.accept = [&](prs::lang::Scene& scene) {
    const prs::lang::Scene drawn = scene;
    const auto start = Clock::now();
    auto rejection = settle(scene);
    const double took_s = SecondsSince(start);
    ++split.settlings;
    split.total_s += took_s;
    if (rejection) {
      ++split.rejected;
      split.rejected_s += took_s;
      if (std::getenv("SETTLE_PROFILE_VERBOSE")) {
        fmt::print("  rejected: {}: {}\n", rejection->culprit, rejection->detail);
      }
    }
    Profile(drawn, scene.settled_s.value_or(0), settle_options.timestep_s, split);
    if (reference_step_s > 0) {
      prs::sim::SettleOptions fine = settle_options;
      fine.timestep_s = reference_step_s;
      prs::lang::Scene fine_scene = drawn;
      const auto fine_start = Clock::now();
      const auto fine_rejection = prs::sim::SettleAndCheck(fine_scene, fine);
      reference_s += SecondsSince(fine_start);
      Compare(scene, rejection.has_value(), fine_scene, fine_rejection.has_value(), reference);
    }
    if (!rejection && check) kept.push_back(scene);
    return rejection;
  };
  prs::sampling::SceneSampler sampler(*program, options);
  const auto start = Clock::now();
  double sampling_s = 0;
  for (int i = 0; i < n; ++i) {
    const auto t = Clock::now();
    (void)sampler.Sample(seed, i);
    sampling_s += SecondsSince(t);
  }
  const double wall_s = SecondsSince(start);
  const double drawing_s = sampling_s - split.total_s - reference_s -
                          (split.export_s + split.compile_s + split.data_s + split.step_s);
  const double build_s = split.export_s + split.compile_s + split.data_s;
  const double settle_s = split.total_s;
  const auto share = [&](double s) { return fmt::format("{:5.1f} %", 100 * s / settle_s); };
  fmt::print("{}: {} settled scenes, {} settlings ({} rejected), seed {}\n", file, n,
             split.settlings, split.rejected, seed);
  fmt::print("settling, as prs runs it:       {:.3f} s ({:.3f} s a kept scene)\n", settle_s,
             settle_s / n);
  fmt::print("  of it in rejected settlings:  {:.3f} s  {}\n", split.rejected_s,
             share(split.rejected_s));
  fmt::print("the instrumented copy (same models, same simulated time):\n");
  fmt::print("  model: export + MJCF          {:.3f} s  {}\n", split.export_s, share(split.export_s));
  fmt::print("  model: MuJoCo's compiler      {:.3f} s  {}\n", split.compile_s,
             share(split.compile_s));
  fmt::print("  model: mjData                 {:.3f} s  {}\n", split.data_s, share(split.data_s));
  fmt::print("  steps ({} of {} ms, {:.1f} s simulated, {:.2f} ms a step):\n", split.steps,
             1e3 * settle_options.timestep_s,
             split.simulated_s, 1e3 * split.step_s / std::max(1L, split.steps));
  fmt::print("    collision                   {:.3f} s  {}\n", split.collision_s,
             share(split.collision_s));
  fmt::print("    constraint solver           {:.3f} s  {}\n", split.constraint_s,
             share(split.constraint_s));
  fmt::print("    the rest of the step        {:.3f} s  {}\n",
             split.step_s - split.collision_s - split.constraint_s,
             share(split.step_s - split.collision_s - split.constraint_s));
  fmt::print("  rest checks, moving bodies, `require settled`: {:.3f} s  {}\n",
             settle_s - build_s - split.step_s, share(settle_s - build_s - split.step_s));
  fmt::print("drawing the scenes (attempts, no settling): {:.3f} s\n", drawing_s);
  const double own_s = wall_s - reference_s - (build_s + split.step_s);
  fmt::print("wall time without the instrumented copy and the reference: {:.3f} s, {:.2f} settled "
             "scenes/s\n", own_s, n / own_s);
  if (reference_step_s > 0) {
    fmt::print("against a {} ms reference (the same drawn scenes): kept by both {}, rejected by both "
               "{}, kept only at {} ms {}, kept only by the reference {}\n",
               1e3 * reference_step_s, reference.both_kept, reference.both_rejected,
               1e3 * settle_options.timestep_s, reference.only_kept, reference.only_reference_kept);
    fmt::print("  where a free body rests, distance to its reference rest: median {:.1f} mm, 90th "
               "percentile {:.1f} mm, largest {:.1f} mm ({} bodies)\n",
               1e3 * Quantile(reference.move_m, 0.5), 1e3 * Quantile(reference.move_m, 0.9),
               1e3 * Quantile(reference.move_m, 1.0), reference.move_m.size());
    fmt::print("  settled_s minus the reference's: median {:.2f} s\n",
               Quantile(reference.settled_ds, 0.5));
  }
  if (check) {
    Checked checked;
    const bool bin = file.find("bin_pile") != std::string::npos;
    for (const prs::lang::Scene& scene : kept) CheckKept(scene, bin, check_step_s, checked);
    fmt::print("checked by MuJoCo on the MJCF export ({} scenes): deepest contact {:.1f} mm, most "
               "a body moved in 1 s at 2 ms steps {:.1f} mm (scenes with one past 1 cm: {}){}\n",
               checked.scenes, 1e3 * checked.deepest_m, 1e3 * checked.most_moved_m,
               checked.moved_past_1cm,
               bin ? fmt::format(", scenes with a body outside the bin {}", checked.outside) : "");
  }
  fmt::print("MuJoCo's stack: {} of {} mjtNums used at most; {} contacts, {} constraint rows at most\n",
             split.max_stack, split.nstack, split.max_con, split.max_efc);
  return 0;
}
