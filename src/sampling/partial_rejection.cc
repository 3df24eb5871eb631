// --sampler partial-rejection: finding the clutter sites of a program (a run with the scene
// checks between objects left out, then probe runs of one object each), the pilot that picks
// the Poisson intensities, and the hard-core draws behind PartialRejectionSampler::Sample.
//
// Why the redraw set is what it is: write B for the objects of overlapping pairs and N(B) for
// the objects (of any site, any numbers) that overlap one of B. Every object of the draw that
// lies in N(B) overlaps a bad one, so it is bad itself: the draw inside N(B) is exactly B, and
// outside it the good objects, which meet none of B. Given B, the objects outside N(B) are
// therefore the Poisson process there conditioned only on not overlapping one another, and a
// fresh process on N(B) completes it to a draw whose law, once no pair overlaps, is the
// hard-core law. A larger redraw set (every object near B, say) would also redraw good objects
// that happen to sit near B, and the good objects left outside would then be conditioned on
// not overlapping those: the law would be wrong. (Checked exactly on small discrete instances
// while this was written; the tests compare with whole-scene rejection.)
#include "sampling/partial_rejection.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace prs::sampling {
namespace {

// Streams of a scene (seed, index), apart from whole-scene rejection's (seed, index) and the
// Gibbs chains' (high bits 10 and 11).
constexpr uint64_t kDrawStream = uint64_t{5} << 60;   // the hard-core draws' numbers
constexpr uint64_t kRunStream = uint64_t{6} << 60;    // a run's draws past its point (none)
constexpr uint64_t kProbeStream = uint64_t{7} << 60;  // a probe's (none)
constexpr uint64_t kPilotSeed = 0x7061727469616c;     // "partial"; the same for every seed
constexpr int kStructureAttempts = 256;

bool IsSameStream(geometry::Rng a, geometry::Rng b) { return a.NextU64() == b.NextU64(); }

// `span`: what in the program makes it unsupported, where that is known.
[[noreturn]] void ThrowUnsupported(const std::string& why,
                                   std::optional<lang::SourceSpan> span = std::nullopt) {
  lang::Diagnostic d;
  d.id = "partial-rejection-unsupported";
  d.has_span = span.has_value();
  if (span) d.span = *span;
  d.message = "--sampler partial-rejection cannot sample this program: " + why;
  d.notes.push_back({{},
                     false,
                     "it samples programs whose random objects are made from their own draws "
                     "alone and otherwise only must not overlap, beside fixed objects "
                     "(docs/sampling.md); use --sampler gibbs (correlated scenes) or the "
                     "default sampler (exact for any program)"});
  throw lang::ScenarioError(std::move(d));
}

std::string DescribeSite(const lang::CompiledProgram& program, const lang::SceneObject& o) {
  const lang::LineColumn at = program.sources.CalcLineColumn(o.span.file, o.span.begin);
  return o.cls->name + " at " + program.sources.path(o.span.file) + ":" + std::to_string(at.line) +
         ":" + std::to_string(at.column);
}

// "20 Cube at bin.prs:4:5 and 3 Gear at bin.prs:6:5".
std::string DescribeCounts(const PartialRejectionPlan& plan) {
  std::string text;
  for (size_t s = 0; s < plan.sites.size(); ++s) {
    if (s > 0) text += s + 1 == plan.sites.size() ? " and " : ", ";
    text += std::to_string(plan.sites[s].ordinals.size()) + " " + plan.sites[s].name;
  }
  return text;
}

bool ChecksLineOfSight(lang::SpecifierKind kind) {
  return kind == lang::SpecifierKind::kVisibleFrom ||
         kind == lang::SpecifierKind::kCompletelyVisibleFrom ||
         kind == lang::SpecifierKind::kNotVisibleFrom;
}

// A candidate object of a site: the numbers it was made from and what they made.
struct Candidate {
  int site = 0;
  std::vector<double> u;
  lang::SceneObject object;
};

// Probe runs and hard-core draws for one thread.
class Engine {
 public:
  Engine(const lang::CompiledProgram& program, const SampleOptions& options,
         const PartialRejectionPlan& plan, const PartialRejectionSettings& settings,
         lang::RunCache* cache)
      : program_(program), options_(options), plan_(plan), settings_(settings), cache_(cache) {}

  // The object of site `s` made alone beside the fixed objects from the numbers u, or nullopt
  // when that run is rejected (the object does not fit on its own).
  std::optional<lang::SceneObject> Probe(int s, const double* u) {
    ++runs_;
    if (options_.live) options_.live->attempts.fetch_add(1, std::memory_order_relaxed);
    lang::RunOptions run = options_.run;
    run.cache = cache_;
    const ClutterSite& site = plan_.sites[static_cast<size_t>(s)];
    run.skip_objects = &site.probe_skips;
    run.stop_after_object = site.ordinals.front();
    run.check_requirements = false;
    run.record_regions = false;
    run.coordinates = {u, site.coordinates};
    const geometry::Rng before(kPilotSeed, kProbeStream);
    geometry::Rng rng = before;
    lang::AttemptResult attempt = lang::RunAttempt(program_, rng, run);
    if (!IsSameStream(before, rng)) {
      ThrowUnsupported(site.name + " draws a varying number of numbers", site.span);
    }
    auto* scene = std::get_if<lang::Scene>(&attempt);
    if (!scene) return std::nullopt;
    lang::SceneObject& object = scene->objects[static_cast<size_t>(site.probe_index)];
    // What the rest of the run would have checked: the later objects against this one.
    for (const lang::SceneObject& later : site.later_fixed) {
      if (lang::DoObjectsCollide(later, object, cache_)) return std::nullopt;
    }
    return std::move(object);
  }

  // One draw of the hard-core process: Poisson candidates of every site, then rounds of
  // redrawing the objects that would overlap those of overlapping pairs (see the top).
  void DrawHardCore(geometry::Rng& rng, std::vector<Candidate>& draw) {
    draw.clear();
    AddFresh(rng, draw, nullptr);
    size_t checked = 0;  // draw[0, checked) overlap none of one another
    for (int64_t round = 0;; ++round) {
      std::vector<bool> bad(draw.size(), false);
      bool any = false;
      for (size_t i = checked; i < draw.size(); ++i) {
        for (size_t j = 0; j < i; ++j) {
          if (lang::DoObjectsCollide(draw[i].object, draw[j].object, cache_)) {
            bad[i] = bad[j] = any = true;
          }
        }
      }
      if (!any) return;
      ++rounds_;
      if (round >= settings_.max_rounds) {
        lang::Diagnostic d;
        d.id = "partial-rejection-too-dense";
        d.span = plan_.sites.front().span;
        d.message = "--sampler partial-rejection gave up on a draw after " +
                    std::to_string(settings_.max_rounds) +
                    " rounds of redrawing overlapping objects: " + DescribeCounts(plan_) +
                    " are too dense for partial rejection sampling";
        d.notes.push_back({{}, false, "use --sampler gibbs for clutter this dense"});
        throw lang::ScenarioError(std::move(d));
      }
      std::vector<Candidate> kept, removed;
      for (size_t i = 0; i < draw.size(); ++i) {
        (bad[i] ? removed : kept).push_back(std::move(draw[i]));
      }
      draw = std::move(kept);
      checked = draw.size();
      AddFresh(rng, draw, &removed);
    }
  }

  int64_t runs() const { return runs_; }
  int64_t rounds() const { return rounds_; }

 private:
  // A Poisson draw of every site's candidates, each kept when it fits on its own and, with
  // `near`, when it overlaps one of `near`.
  void AddFresh(geometry::Rng& rng, std::vector<Candidate>& draw,
                const std::vector<Candidate>* near) {
    for (size_t s = 0; s < plan_.sites.size(); ++s) {
      const ClutterSite& site = plan_.sites[s];
      const int64_t count = DrawPoisson(rng, site.intensity);
      for (int64_t m = 0; m < count; ++m) {
        Candidate c;
        c.site = static_cast<int>(s);
        c.u.resize(static_cast<size_t>(site.coordinates));
        for (double& x : c.u) x = rng.Uniform01();
        std::optional<lang::SceneObject> object = Probe(c.site, c.u.data());
        if (!object) continue;
        if (near) {
          const bool overlaps = std::any_of(near->begin(), near->end(), [&](const Candidate& b) {
            return lang::DoObjectsCollide(*object, b.object, cache_);
          });
          if (!overlaps) continue;
        }
        c.object = std::move(*object);
        draw.push_back(std::move(c));
      }
    }
  }

  const lang::CompiledProgram& program_;
  const SampleOptions& options_;
  const PartialRejectionPlan& plan_;
  const PartialRejectionSettings& settings_;
  lang::RunCache* cache_;
  int64_t runs_ = 0;
  int64_t rounds_ = 0;
};

// Whether a draw holds as many objects of each site as the program makes.
bool HasProgramCounts(const PartialRejectionPlan& plan, const std::vector<Candidate>& draw,
                      std::vector<int>& counts) {
  counts.assign(plan.sites.size(), 0);
  for (const Candidate& c : draw) ++counts[static_cast<size_t>(c.site)];
  for (size_t s = 0; s < plan.sites.size(); ++s) {
    if (counts[s] != static_cast<int>(plan.sites[s].ordinals.size())) return false;
  }
  return true;
}

// The sites of `program`: a run with the checks between objects left out names every object,
// and probe runs tell what each site's object draws. Throws when the program is outside the
// sampler's reach.
PartialRejectionPlan FindSites(const lang::CompiledProgram& program, const SampleOptions& options,
                               lang::RunCache* cache) {
  if (options.run.mode == lang::SamplingMode::kNaive) {
    ThrowUnsupported("--naive places objects anywhere in the workspace and checks afterwards");
  }
  std::map<std::pair<lang::FileId, uint32_t>, const lang::ObjectPlan*> plan_at;
  for (const auto& [node, plan] : program.plans) {
    for (const lang::Specifier& s : node->specifiers) {
      if (ChecksLineOfSight(s.kind)) {
        ThrowUnsupported(
            "a line-of-sight specifier makes an object's validity depend on every "
            "other object",
            s.span);
      }
    }
    plan_at[{node->class_name.span.file, node->class_name.span.begin}] = &plan;
  }
  // A run that makes every object: collisions and requirements are what the sampler imposes.
  lang::RunOptions run = options.run;
  run.cache = nullptr;
  run.check_requirements = false;
  run.check_collisions = false;
  std::optional<lang::Scene> scene;
  std::vector<lang::CoordinateInfo> log;
  std::optional<lang::Rejection> last;
  for (int attempt = 0; attempt < kStructureAttempts && !scene; ++attempt) {
    geometry::Rng rng(kPilotSeed, static_cast<uint64_t>(attempt));
    log.clear();
    run.coordinates = {nullptr, 0, &log};
    lang::AttemptResult result = lang::RunAttempt(program, rng, run);
    if (auto* s = std::get_if<lang::Scene>(&result)) {
      scene = std::move(*s);
    } else {
      last = std::get<lang::Rejection>(result);
      if (last->certain) break;
    }
  }
  if (!scene) {
    ThrowUnsupported("no run made every object even with overlaps and requirements allowed (" +
                         std::string(lang::RejectionKindName(last->kind)) + ": " + last->culprit +
                         ")",
                     last->span);
  }
  PartialRejectionPlan plan;
  plan.dimension = static_cast<int>(log.size());
  std::map<std::pair<lang::FileId, std::string>, size_t> site_of;
  for (size_t i = 0; i < scene->objects.size(); ++i) {
    const lang::SceneObject& o = scene->objects[i];
    if (o.fixed) continue;
    const auto found = plan_at.find({o.span.file, o.span.begin});
    if (found == plan_at.end() || !found->second->own_draws_only) {
      ThrowUnsupported(o.DisplayName(static_cast<int>(i)) +
                           " is not made from its own draws alone (it reads a random value, "
                           "another object, or a name bound more than once)",
                       o.span);
    }
    // Sites of the same text in the same module make objects of the same law (what they read
    // is fixed from before the first of them on): one site, whose objects are exchangeable.
    const std::string_view text = program.sources.text(o.span.file);
    auto [it, added] = site_of.emplace(
        std::make_pair(o.span.file,
                       std::string(text.substr(o.span.begin, o.span.end - o.span.begin))),
        plan.sites.size());
    if (added) {
      ClutterSite site;
      site.name = DescribeSite(program, o);
      site.span = o.span;
      plan.sites.push_back(site);
    }
    plan.sites[it->second].ordinals.push_back(static_cast<int>(i));
  }
  if (plan.sites.empty()) ThrowUnsupported("it makes no random objects");
  // The fixed part alone: accepted, and drawing nothing.
  std::vector<bool> skip_all(scene->objects.size(), false);
  for (const ClutterSite& site : plan.sites) {
    for (int o : site.ordinals) skip_all[static_cast<size_t>(o)] = true;
  }
  lang::RunOptions probe = options.run;
  probe.cache = cache;
  probe.check_requirements = false;
  std::vector<int> fixed_ordinals;
  for (size_t i = 0; i < scene->objects.size(); ++i) {
    if (scene->objects[i].fixed) fixed_ordinals.push_back(static_cast<int>(i));
  }
  std::vector<lang::SceneObject> fixed;  // made by the fixed part alone, in order
  {
    std::vector<lang::CoordinateInfo> rest_log;
    probe.skip_objects = &skip_all;
    probe.coordinates = {nullptr, 0, &rest_log};
    geometry::Rng rng(kPilotSeed, kProbeStream);
    lang::AttemptResult rest = lang::RunAttempt(program, rng, probe);
    if (!rest_log.empty()) {
      ThrowUnsupported(
          "it draws numbers outside its random objects (" + rest_log.front().name + ")",
          rest_log.front().span);
    }
    if (auto* rejection = std::get_if<lang::Rejection>(&rest)) {
      ThrowUnsupported("its fixed objects alone are rejected (" +
                           std::string(lang::RejectionKindName(rejection->kind)) + ": " +
                           rejection->culprit + ")",
                       rejection->span);
    }
    fixed = std::move(std::get<lang::Scene>(rest).objects);
    if (fixed.size() != fixed_ordinals.size()) {
      ThrowUnsupported("its fixed objects change when its random objects are left out");
    }
  }
  int drawn = 0;
  for (ClutterSite& site : plan.sites) {
    site.probe_skips = skip_all;
    site.probe_skips[static_cast<size_t>(site.ordinals.front())] = false;
    site.probe_index = 0;
    for (size_t k = 0; k < fixed_ordinals.size(); ++k) {
      if (fixed_ordinals[k] < site.ordinals.front()) {
        ++site.probe_index;
      } else {
        site.later_fixed.push_back(fixed[k]);
      }
    }
    std::vector<lang::CoordinateInfo> site_log;
    probe.skip_objects = &site.probe_skips;
    probe.stop_after_object = site.ordinals.front();
    probe.coordinates = {nullptr, 0, &site_log};
    geometry::Rng rng(kPilotSeed, kProbeStream);
    (void)lang::RunAttempt(program, rng, probe);
    site.coordinates = static_cast<int>(site_log.size());
    drawn += site.coordinates * static_cast<int>(site.ordinals.size());
  }
  if (drawn != plan.dimension) {
    ThrowUnsupported("its objects draw " + std::to_string(plan.dimension) +
                     " numbers together but " + std::to_string(drawn) +
                     " one at a time (a varying number of draws)");
  }
  return plan;
}

}  // namespace

int64_t DrawPoisson(geometry::Rng& rng, double mean) {
  int64_t n = 0;
  for (double left = std::max(0.0, mean); left > 0;) {
    const double piece = std::min(left, 64.0);
    left -= piece;
    const double floor = std::exp(-piece);
    for (double p = rng.Uniform01(); p > floor; p *= rng.Uniform01()) ++n;
  }
  return n;
}

const PartialRejectionPlan& PartialRejectionRequest::Plan(const lang::CompiledProgram& program,
                                                          const SampleOptions& options) {
  std::lock_guard lock(mutex_);
  if (plan_) return *plan_;
  auto cache = lang::MakeRunCache();
  PartialRejectionPlan plan = FindSites(program, options, cache.get());
  // The intensities: each site's expected count held near its number of objects, by the
  // pilot's draws (any intensity gives exact scenes; these make the counts match often).
  for (ClutterSite& site : plan.sites) site.intensity = static_cast<double>(site.ordinals.size());
  Engine engine(program, options, plan, settings_, cache.get());
  geometry::Rng rng(kPilotSeed, kDrawStream);
  std::vector<Candidate> draw;
  std::vector<int> counts;
  int matched = 0;
  for (int step = 0; step <= settings_.pilot_iterations; ++step) {
    std::vector<double> totals(plan.sites.size(), 0.0);
    matched = 0;
    for (int d = 0; d < settings_.pilot_draws_per_step; ++d) {
      engine.DrawHardCore(rng, draw);
      matched += HasProgramCounts(plan, draw, counts) ? 1 : 0;
      for (size_t s = 0; s < counts.size(); ++s) totals[s] += counts[s];
    }
    if (step == settings_.pilot_iterations) break;  // the last step only measures
    for (size_t s = 0; s < plan.sites.size(); ++s) {
      const double mean = totals[s] / settings_.pilot_draws_per_step;
      const double wanted = static_cast<double>(plan.sites[s].ordinals.size());
      plan.sites[s].intensity *= std::clamp(wanted / std::max(mean, 0.5), 0.5, 2.0);
    }
  }
  plan.pilot_draws = int64_t{settings_.pilot_draws_per_step} * (settings_.pilot_iterations + 1);
  plan.mean_rounds = static_cast<double>(engine.rounds()) / static_cast<double>(plan.pilot_draws);
  plan.mean_probes = static_cast<double>(engine.runs()) / static_cast<double>(plan.pilot_draws);
  plan.count_acceptance = static_cast<double>(matched) / settings_.pilot_draws_per_step;
  plan_ = std::move(plan);
  return *plan_;
}

std::optional<PartialRejectionPlan> PartialRejectionRequest::plan() const {
  std::lock_guard lock(mutex_);
  return plan_;
}

PartialRejectionSampler::PartialRejectionSampler(const lang::CompiledProgram& program,
                                                 const SampleOptions& options)
    : program_(program), options_(options), cache_(lang::MakeRunCache()) {}

PartialRejectionSampler::~PartialRejectionSampler() = default;

SampledScene PartialRejectionSampler::Sample(uint64_t seed, uint64_t index) {
  PartialRejectionRequest& request = *options_.partial_rejection;
  const PartialRejectionPlan& plan = request.Plan(program_, options_);
  Engine engine(program_, options_, plan, request.settings(), cache_.get());
  SampledScene result;
  result.seed = seed;
  result.index = index;
  geometry::Rng rng(seed, kDrawStream | index);
  std::set<std::pair<lang::RejectionKind, std::string>> explained;
  // Where each creation ordinal's numbers go: (site, slot), in the order a run reads them.
  std::vector<std::pair<int, int>> order;
  for (size_t s = 0; s < plan.sites.size(); ++s) {
    for (size_t j = 0; j < plan.sites[s].ordinals.size(); ++j) {
      order.emplace_back(static_cast<int>(s), static_cast<int>(j));
    }
  }
  std::sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
    return plan.sites[a.first].ordinals[a.second] < plan.sites[b.first].ordinals[b.second];
  });
  std::vector<Candidate> draw;
  std::vector<int> counts;
  std::vector<std::vector<const Candidate*>> slots(plan.sites.size());
  std::vector<double> u;
  int64_t finals = 0;
  for (int64_t draws = 0; draws < options_.max_attempts; ++draws) {
    engine.DrawHardCore(rng, draw);
    if (!HasProgramCounts(plan, draw, counts)) continue;
    // The objects of a site in random order: its creations are exchangeable.
    for (auto& slot : slots) slot.clear();
    for (const Candidate& c : draw) slots[static_cast<size_t>(c.site)].push_back(&c);
    for (auto& slot : slots) {
      for (size_t k = slot.size(); k > 1; --k) {
        std::swap(slot[k - 1], slot[static_cast<size_t>(rng.UniformInt(0, int64_t(k) - 1))]);
      }
    }
    u.clear();
    for (const auto& [s, j] : order) {
      const std::vector<double>& v = slots[static_cast<size_t>(s)][static_cast<size_t>(j)]->u;
      u.insert(u.end(), v.begin(), v.end());
    }
    // The program at those numbers: its requirements (and any scene test) accept or reject.
    ++finals;
    if (options_.live) options_.live->attempts.fetch_add(1, std::memory_order_relaxed);
    lang::RunOptions run = options_.run;
    run.cache = cache_.get();
    run.explained = &explained;
    run.coordinates = {u.data(), static_cast<int>(u.size())};
    geometry::Rng stream(seed, kRunStream | index);
    lang::AttemptResult attempt = lang::RunAttempt(program_, stream, run);
    if (auto* scene = std::get_if<lang::Scene>(&attempt)) {
      for (const auto& [s, j] : order) {
        const lang::SceneObject& made = scene->objects[static_cast<size_t>(
            plan.sites[static_cast<size_t>(s)].ordinals[static_cast<size_t>(j)])];
        const lang::SceneObject& probed =
            slots[static_cast<size_t>(s)][static_cast<size_t>(j)]->object;
        if (made.p_WO != probed.p_WO || made.R_WO.coeffs() != probed.R_WO.coeffs()) {
          ThrowUnsupported(plan.sites[static_cast<size_t>(s)].name +
                               " makes a different object alone than in the whole scene",
                           plan.sites[static_cast<size_t>(s)].span);
        }
      }
      std::optional<lang::Rejection> failed =
          options_.accept ? options_.accept(*scene) : std::nullopt;
      if (!failed) {
        result.scene = std::move(*scene);
        result.coordinates = u;
        result.attempts = engine.runs() + finals;
        return result;
      }
      attempt = std::move(*failed);
    }
    if (options_.live) options_.live->rejections.fetch_add(1, std::memory_order_relaxed);
    const lang::Rejection& rejection = std::get<lang::Rejection>(attempt);
    result.rejections.Add(rejection);
    explained.emplace(rejection.kind, rejection.culprit);
  }
  result.attempts = engine.runs() + finals;
  if (result.rejections.total == 0) {
    lang::Diagnostic d;
    d.id = "sampling-failed";
    d.span = plan.sites.front().span;
    d.message = "--sampler partial-rejection drew " + std::to_string(options_.max_attempts) +
                " hard-core draws and none held the program's numbers of objects (" +
                DescribeCounts(plan) + ")";
    d.notes.push_back({{}, false, "raise the limit with --max-attempts, or use --sampler gibbs"});
    throw lang::ScenarioError(std::move(d));
  }
  ThrowSamplingFailure(result.rejections, finals, 0, lang::RejectionKind::kUnstable);
}

}  // namespace prs::sampling
