// Campaign directories: init (copy the spec, write the plan), shard files with sidecars, status
// from the files, running one shard, merging in index order.
#include "campaign/campaign.h"

#include <fcntl.h>
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "campaign/files.h"
#include "campaign/search_campaign.h"
#include "output/line_writer.h"
#include "output/scene_json.h"
#include "sampling/batch.h"
#include "sampling/gibbs.h"
#include "sampling/partial_rejection.h"
#include "search/like.h"

namespace prs::campaign {
namespace fs = std::filesystem;
namespace {

nlohmann::json ToJson(const CampaignSpec& s) {
  nlohmann::json params = nlohmann::json::array();
  for (const auto& [name, value] : s.params) params.push_back({name, value});
  return {{"format", "prs-campaign/1"},
          {"id", s.id},
          {"kind", s.kind},
          {"main_file", s.main_file},
          {"scenario_words", s.scenario_words},
          {"params", params},
          {"naive", s.naive},
          {"sampler", s.sampler},
          {"max_attempts", s.max_attempts},
          {"seed", s.seed},
          {"count", s.count},
          {"shard_size", s.shard_size},
          {"controller", s.controller},
          {"exec", s.exec},
          {"timeout_s", s.timeout_s},
          {"persistent", s.persistent},
          {"startup_timeout_s", s.startup_timeout_s},
          {"perception", s.perception},
          {"spec_hash", s.spec_hash},
          {"version", s.version},
          {"strategy", s.strategy},
          {"batch", s.batch},
          {"generation_sizes", s.generation_sizes},
          {"stable_s", s.stable_s},
          {"stable_move_m", s.stable_move_m},
          {"stable_turn_deg", s.stable_turn_deg},
          {"settle_s", s.settle_s},
          {"dataset",
           s.kind != "dataset" ? nlohmann::json()
                               : nlohmann::json{{"cameras", s.dataset.cameras},
                                                {"width", s.dataset.width},
                                                {"height", s.dataset.height},
                                                {"bop", s.dataset.bop},
                                                {"coco", s.dataset.coco},
                                                {"labels", s.dataset.labels},
                                                {"jpeg", s.dataset.jpeg},
                                                {"images_per_chunk", s.dataset.images_per_chunk}}}};
}

std::string SidecarPath(const std::string& dir, uint64_t k) {
  return ShardPath(dir, k) + ".done.json";
}

}  // namespace

std::string ReadFileText(const std::string& path, bool* ok) {
  std::ifstream in(path, std::ios::binary);
  *ok = static_cast<bool>(in);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}


// A search or estimate campaign's generations are cut into shards one by one.
namespace {
uint64_t CeilDiv(uint64_t a, uint64_t b) { return (a + b - 1) / b; }
}  // namespace

sampling::SampleOptions MakeSampleOptions(const CampaignSpec& spec) {
  sampling::SampleOptions sample;
  sample.max_attempts = spec.max_attempts;
  sample.run.mode = spec.naive ? lang::SamplingMode::kNaive : lang::SamplingMode::kRegion;
  if (spec.sampler == "gibbs") sample.gibbs = std::make_shared<sampling::GibbsRequest>();
  if (spec.sampler == "partial-rejection") {
    sample.partial_rejection = std::make_shared<sampling::PartialRejectionRequest>();
  }
  return sample;
}

std::vector<uint64_t> CampaignSpec::sizes() const {
  if (kind == "estimate") return generation_sizes;
  if (batch == 0) return {count};
  std::vector<uint64_t> sizes(count / batch, batch);
  if (count % batch > 0) sizes.push_back(count % batch);
  return sizes;
}

uint64_t CampaignSpec::shards() const {
  uint64_t shards = 0;
  for (uint64_t size : sizes()) shards += CeilDiv(size, shard_size);
  return shards;
}

uint64_t CampaignSpec::generation(uint64_t k) const {
  const std::vector<uint64_t> all = sizes();
  for (uint64_t g = 0; g < all.size(); ++g) {
    const uint64_t here = CeilDiv(all[g], shard_size);
    if (k < here) return g;
    k -= here;
  }
  return all.size();
}

uint64_t CampaignSpec::generations() const { return sizes().size(); }

uint64_t CampaignSpec::first(uint64_t k) const {
  uint64_t start = 0;
  for (uint64_t size : sizes()) {
    const uint64_t here = CeilDiv(size, shard_size);
    if (k < here) return start + k * shard_size;
    k -= here;
    start += size;
  }
  return start;
}

uint64_t CampaignSpec::size(uint64_t k) const {
  for (uint64_t size : sizes()) {
    const uint64_t here = CeilDiv(size, shard_size);
    if (k < here) return std::min(shard_size, size - k * shard_size);
    k -= here;
  }
  return 0;
}

std::vector<uint64_t> CampaignSpec::generation_shards(uint64_t g) const {
  std::vector<uint64_t> shards_of_g;
  const std::vector<uint64_t> all = sizes();
  uint64_t k = 0;
  for (uint64_t h = 0; h < all.size() && h <= g; ++h) {
    const uint64_t here = CeilDiv(all[h], shard_size);
    for (uint64_t i = 0; i < here; ++i, ++k) {
      if (h == g) shards_of_g.push_back(k);
    }
  }
  return shards_of_g;
}

std::string ShardPath(const std::string& dir, uint64_t k) {
  return fmt::format("{}/shards/shard-{:05d}.jsonl", dir, k);
}

std::string DatasetShardPath(const std::string& dir, uint64_t k) {
  return fmt::format("{}/shards/shard-{:05d}", dir, k);
}

CampaignSpec InitCampaign(const std::string& dir, const lang::CompiledProgram& program,
                          CampaignSpec spec) {
  if (spec.count == 0 || spec.shard_size == 0) {
    throw CampaignError("a campaign needs at least one scene (-n) and a shard size of at least 1");
  }
  if (spec.kind == "search") {
    if (spec.batch == 0) spec.batch = static_cast<uint64_t>(search::DefaultBatch(spec.count));
    try {
      search::SearchPlanner check(program, MakeSearchOptions(spec));
    } catch (const search::NothingToSearch& error) {
      throw CampaignError(error.what());
    }
  } else if (spec.batch > 0) {
    throw CampaignError("a generation size is for search campaigns only");
  }
  if (spec.kind == "estimate") {
    try {
      search::EstimatePlanner check(program, MakeEstimateOptions(spec));
      const int dimension =
          int(sampling::DescribeCoordinates(program, MakeSampleOptions(spec)).size());
      spec.generation_sizes.clear();
      for (int64_t size : search::CalcEstimateLayout(int64_t(spec.count), dimension)) {
        spec.generation_sizes.push_back(uint64_t(size));
      }
    } catch (const search::NothingToSearch& error) {
      throw CampaignError(std::string(error.what()) +
                          ": every scene is the same, so it fails always or never");
    } catch (const std::invalid_argument& error) {  // a budget too small
      throw CampaignError(error.what());
    }
  }
  // Files the program reads besides its modules must sit below its directory to be carried.
  const std::vector<lang::ProgramResource> resources = lang::ListResources(program);
  for (const lang::ProgramResource& r : resources) {
    const fs::path name(r.name);
    const bool inside =
        name.is_relative() &&
        std::none_of(name.begin(), name.end(), [](const fs::path& part) { return part == ".."; });
    if (!inside) {
      throw CampaignError("the file '" + r.name +
                          "' (an arm or a mesh) is not below the scenario's directory, so "
                          "a campaign cannot carry it; put it next to the .prs file and name it "
                          "by a relative path");
    }
  }
  std::error_code error;
  if (fs::exists(dir, error) && !fs::is_empty(dir, error)) {
    throw CampaignError(dir + " exists and is not empty; a campaign needs a directory of its own");
  }
  fs::create_directories(fs::path(dir) / "spec", error);
  fs::create_directories(fs::path(dir) / "shards", error);
  if (error) throw CampaignError("cannot create " + dir + ": " + error.message());
  std::map<std::string, std::string> copied;  // name -> original path
  for (size_t f = 0; f < program.sources.file_count(); ++f) {
    const std::string& path = program.sources.path(static_cast<lang::FileId>(f));
    const std::string name = fs::path(path).filename().string();
    const auto [it, fresh] = copied.emplace(name, path);
    if (!fresh) {
      throw CampaignError("two files of the scenario are both called " + name + " (" + it->second +
                          " and " + path + "); rename one so the campaign can hold both");
    }
    WriteFileAtomically(fmt::format("{}/spec/{}", dir, name),
                        std::string(program.sources.text(static_cast<lang::FileId>(f))));
    if (f == 0) spec.main_file = "spec/" + name;
  }
  // URDF files, where the copied modules will look for them: by the name the program gives.
  for (const lang::ProgramResource& r : resources) {
    fs::create_directories((fs::path(dir) / "spec" / r.name).parent_path(), error);
    WriteFileAtomically(fmt::format("{}/spec/{}", dir, r.name), r.text);
  }
  spec.spec_hash = search::CalcSpecHash(program);
  spec.id = fmt::format(
      "{:016x}", search::CalcFnv1a(
                     spec.spec_hash + std::to_string(::getpid()) +
                     std::to_string(std::chrono::system_clock::now().time_since_epoch().count())));
  WriteFileAtomically(dir + "/campaign.json", ToJson(spec).dump(2) + "\n");
  return spec;
}

CampaignSpec ReadCampaign(const std::string& dir) {
  const std::string path = dir + "/campaign.json";
  bool ok = false;
  const std::string text = ReadFileText(path, &ok);
  if (!ok) {
    throw CampaignError("cannot read " + path + ": is " + dir +
                        " a campaign directory (made by prs campaign init)?");
  }
  const auto j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  try {
    if (!j.is_object() || j.value("format", "") != "prs-campaign/1") throw std::exception();
    CampaignSpec s;
    s.id = j.at("id");
    s.kind = j.at("kind");
    s.main_file = j.at("main_file");
    s.scenario_words = j.at("scenario_words").get<std::vector<std::string>>();
    for (const auto& p : j.at("params")) s.params.emplace_back(p.at(0), p.at(1));
    s.naive = j.at("naive");
    s.sampler = j.value("sampler", "rejection");
    s.max_attempts = j.at("max_attempts");
    s.seed = j.at("seed");
    s.count = j.at("count");
    s.shard_size = j.at("shard_size");
    s.controller = j.at("controller");
    s.exec = j.at("exec");
    s.timeout_s = j.at("timeout_s");
    s.persistent = j.value("persistent", false);
    s.startup_timeout_s = j.value("startup_timeout_s", 120.0);
    s.perception = j.value("perception", "");
    s.spec_hash = j.at("spec_hash");
    s.version = j.at("version");
    s.strategy = j.value("strategy", "");
    s.batch = j.value("batch", uint64_t{0});
    s.generation_sizes = j.value("generation_sizes", std::vector<uint64_t>{});
    s.stable_s = j.value("stable_s", 0.0);
    s.stable_move_m = j.value("stable_move_m", 0.01);
    s.stable_turn_deg = j.value("stable_turn_deg", 5.0);
    s.settle_s = j.value("settle_s", 0.0);
    if (s.kind == "dataset") {
      const auto& d = j.at("dataset");
      s.dataset.cameras = d.at("cameras").get<std::vector<std::string>>();
      s.dataset.width = d.at("width");
      s.dataset.height = d.at("height");
      s.dataset.bop = d.at("bop");
      s.dataset.coco = d.at("coco");
      s.dataset.labels = d.at("labels").get<std::vector<std::string>>();
      s.dataset.images_per_chunk = d.at("images_per_chunk");
      s.dataset.jpeg = d.value("jpeg", false);
      if (s.dataset.cameras.empty()) throw std::exception();
    }
    uint64_t layout = 0;
    for (uint64_t size : s.generation_sizes) layout += size;
    if ((s.kind != "test" && s.kind != "sample" && s.kind != "search" && s.kind != "estimate" &&
         s.kind != "dataset") ||
        s.count == 0 || s.shard_size == 0 || (s.kind == "search") != (s.batch > 0) ||
        (s.kind == "estimate") != (layout == s.count)) {
      throw std::exception();
    }
    return s;
  } catch (const std::exception&) {
    throw CampaignError(path + " is not a campaign file this prs can read (format prs-campaign/1)");
  }
}

std::unique_ptr<lang::CompiledProgram> CompileCampaign(const std::string& dir,
                                                       const CampaignSpec& spec) {
  lang::DiagnosticEngine diagnostics;
  lang::CompileOptions options;
  options.search_path = {dir + "/spec"};
  options.param_overrides = spec.params;
  auto program = lang::CompileFile(dir + "/" + spec.main_file, options, diagnostics);
  if (diagnostics.has_errors()) {
    std::string text;
    for (const auto& d : diagnostics.diagnostics())
      text += lang::RenderDiagnostic(d, program->sources);
    throw CampaignError("the campaign's copy of the scenario does not compile:\n" + text);
  }
  if (search::CalcSpecHash(*program) != spec.spec_hash) {
    throw CampaignError("the scenario in " + dir + "/spec changed since prs campaign init (spec " +
                        search::CalcSpecHash(*program) + ", the campaign's is " + spec.spec_hash +
                        "); start a new campaign for a changed scenario");
  }
  return program;
}

ShardStatus CheckShard(const std::string& dir, const CampaignSpec& spec, uint64_t k) {
  const std::string path = ShardPath(dir, k);
  std::error_code error;
  const bool data = fs::exists(path, error);
  const bool sidecar = fs::exists(SidecarPath(dir, k), error);
  if (!data || !sidecar) {
    if (fs::exists(path + ".partial", error))
      return {ShardStatus::State::kRunning, path + ".partial"};
    if (data)
      return {ShardStatus::State::kBad, "its .done.json is missing (interrupted at the end?)"};
    return {ShardStatus::State::kMissing, ""};
  }
  bool ok = false;
  const auto meta = nlohmann::json::parse(ReadFileText(SidecarPath(dir, k), &ok), nullptr, false);
  const std::string content = ReadFileText(path, &ok);
  if (!meta.is_object()) return {ShardStatus::State::kBad, "its .done.json is not JSON"};
  if (meta.value("campaign", "") != spec.id) {
    return {ShardStatus::State::kBad, "it was written by another campaign"};
  }
  if (meta.value("spec", "") != spec.spec_hash || meta.value("version", "") != spec.version) {
    return {ShardStatus::State::kBad, "it was written for another spec or prs version"};
  }
  if (meta.value("bytes", uint64_t{0}) != content.size() ||
      meta.value("checksum", "") != fmt::format("{:016x}", search::CalcFnv1a(content))) {
    return {ShardStatus::State::kBad, "its file was changed or truncated after it was written"};
  }
  if (meta.value("lines", uint64_t{0}) != spec.size(k)) {
    return {ShardStatus::State::kBad, "it holds the wrong number of lines"};
  }
  if (spec.kind == "dataset" && !fs::is_directory(DatasetShardPath(dir, k), error)) {
    return {ShardStatus::State::kBad, "its dataset folder " + DatasetShardPath(dir, k) +
                                          " is missing (moved or deleted after it was written)"};
  }
  return {ShardStatus::State::kDone, ""};
}

void WriteShard(const std::string& dir, const CampaignSpec& spec, uint64_t k,
                const std::vector<std::string>& lines) {
  std::error_code error;
  fs::remove(SidecarPath(dir, k), error);  // an old sidecar never vouches for new data
  std::string content;
  for (const std::string& line : lines) content += line + "\n";
  WriteFileAtomically(ShardPath(dir, k), content);
  const nlohmann::json meta = {{"campaign", spec.id},
                               {"shard", k},
                               {"spec", spec.spec_hash},
                               {"version", spec.version},
                               {"lines", lines.size()},
                               {"bytes", content.size()},
                               {"checksum", fmt::format("{:016x}", search::CalcFnv1a(content))}};
  WriteFileAtomically(SidecarPath(dir, k), meta.dump() + "\n");
}

void RunShard(const std::string& dir, const CampaignSpec& spec,
              const lang::CompiledProgram& program, uint64_t k,
              const harness::ControllerFactory* factory, int threads,
              const std::atomic<bool>* cancel, const ShardHooks& hooks) {
  if (k >= spec.shards()) {
    throw CampaignError(
        fmt::format("there is no shard {}: the campaign has shards 0 to {}", k, spec.shards() - 1));
  }
  if ((spec.stable_s > 0 || spec.settle_s > 0) && !hooks.accept) {
    throw std::invalid_argument(
        "RunShard: the campaign asks for --stable or --settle but no check was given");
  }
  sampling::SampleOptions sample = MakeSampleOptions(spec);
  sample.accept = hooks.accept;
  std::vector<std::string> lines;
  if (spec.kind != "sample" && spec.kind != "dataset" && !factory)
    throw std::invalid_argument("RunShard: no controller");
  if (spec.planned()) {
    lines = RunSearchShard(dir, spec, program, k, *factory, threads, cancel, hooks);
  } else if (spec.kind == "test") {
    harness::RunOptions run;
    run.sample = sample;
    run.seed = spec.seed;
    run.start = spec.first(k);
    run.count = static_cast<int64_t>(spec.size(k));
    run.threads = threads;
    run.scenario_args = spec.scenario_words;
    run.spec_hash = spec.spec_hash;
    run.scene_options = harness::SceneOptionsOf(spec.scenario_words);
    run.cancel = cancel;
    run.on_warning = hooks.on_warning;
    run.on_record = [&](const harness::EpisodeRecord& r) {
      lines.push_back(harness::FormatRecordJson(r));
    };
    harness::RunEpisodes(program, *factory, run);
  } else {
    sampling::BatchOptions batch;
    batch.sample = sample;
    batch.seed = spec.seed;
    batch.start = spec.first(k);
    batch.count = static_cast<int64_t>(spec.size(k));
    batch.threads = threads;
    batch.cancel = cancel;
    const auto keep_line = [&](sampling::BatchScene&& s) {
      lines.push_back(output::FormatSceneJson(s.sampled));
    };
    if (spec.kind == "dataset") {
      // A re-run rewrites the shard: its sidecar goes first, so that nothing vouches for a
      // dataset folder while it is being replaced.
      std::error_code error;
      fs::remove(SidecarPath(dir, k), error);
      dataset::DatasetOptions options = spec.dataset;
      options.dir = DatasetShardPath(dir, k);
      fs::remove_all(options.dir, error);
      fs::remove_all(options.dir + ".partial", error);
      dataset::DatasetWriter writer(options, dataset::ListClassIds(program));
      dataset::AddSampledScenes(writer, program, batch, {.consume = keep_line});
      writer.Finish();
    } else {
      sampling::SampleBatch(program, batch, {.prepare = {}, .consume = keep_line});
    }
  }
  WriteShard(dir, spec, k, lines);
}

void MergeDatasetShards(const std::string& dir, const CampaignSpec& spec, const std::string& out) {
  if (spec.kind != "dataset") throw CampaignError(dir + " is a " + spec.kind + " campaign");
  MergeShards(dir, spec, /*partial=*/false, nullptr);  // throws naming the shards not done
  std::vector<std::string> parts;
  for (uint64_t k = 0; k < spec.shards(); ++k) parts.push_back(DatasetShardPath(dir, k));
  dataset::MergeDatasets(parts, out);
}

std::vector<std::string> MergeShards(const std::string& dir, const CampaignSpec& spec, bool partial,
                                     std::vector<uint64_t>* skipped) {
  if (spec.kind == "estimate" && partial) {
    throw CampaignError(
        "an estimate's weights come from every generation's records, so its shards merge only "
        "when all are done: run the rest (prs campaign status " +
        dir + " names them)");
  }
  std::vector<std::string> lines;
  std::string not_done;
  for (uint64_t k = 0; k < spec.shards(); ++k) {
    const ShardStatus status = CheckShard(dir, spec, k);
    if (status.state != ShardStatus::State::kDone) {
      if (skipped) skipped->push_back(k);
      if (not_done.size() < 200) not_done += fmt::format("{}{}", not_done.empty() ? "" : ", ", k);
      continue;
    }
    bool ok = false;
    std::stringstream content(ReadFileText(ShardPath(dir, k), &ok));
    for (std::string line; std::getline(content, line);) lines.push_back(line);
  }
  if (!not_done.empty() && !partial) {
    throw CampaignError("shards not done: " + not_done +
                        " (prs campaign status says why; run them, or merge with --partial)");
  }
  return lines;
}

}  // namespace prs::campaign
