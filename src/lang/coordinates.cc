// The interpreter's draws: every random number of an attempt is made here, from the attempt's
// scene coordinates while they last (RunOptions::coordinates) and from the Rng stream after,
// with each coordinate named after what it decides (docs/search.md, "Scene coordinates").
#include <cmath>
#include <filesystem>

#include "lang/interp_internal.h"

namespace prs::lang::internal {

std::string Interpreter::NameCoordinate(const char* draw, SourceSpan span, int object) const {
  if (object >= 0 && object < static_cast<int>(scene_.objects.size())) {
    return scene_.objects[object].DisplayName(object) + ".position";
  }
  if (naming_object_ >= 0 && naming_property_ &&
      naming_object_ < static_cast<int>(scene_.objects.size())) {
    return scene_.objects[naming_object_].DisplayName(naming_object_) + "." +
           (naming_property_->empty() ? std::string("orientation") : *naming_property_);
  }
  const LineColumn where = program_.sources.CalcLineColumn(span.file, span.begin);
  return std::string(draw) + " at " +
         std::filesystem::path(program_.sources.path(span.file)).filename().string() + ":" +
         std::to_string(where.line) + ":" + std::to_string(where.column);
}

const double* Interpreter::TakeCoordinates(int k, const char* draw, SourceSpan span, int object) {
  const CoordinateInput& in = options_.coordinates;
  if (in.log && k > 0 && in.log->size() < kMaxLoggedCoordinates) {
    const std::string name = NameCoordinate(draw, span, object);
    for (int j = 0; j < k; ++j) {
      in.log->push_back({k > 1 ? name + "[" + std::to_string(j) + "]" : name, draw, span});
    }
  }
  if (!in.values || coordinates_done_ || k <= 0) return nullptr;
  if (next_coordinate_ + k > in.size) {
    coordinates_done_ = true;  // this draw and every later one read the stream
    return nullptr;
  }
  const double* u = in.values + next_coordinate_;
  next_coordinate_ += k;
  return u;
}

double Interpreter::DrawUniform(double lo, double hi, SourceSpan span, const char* draw) {
  ++draws_;
  if (const double* u = TakeCoordinates(1, draw, span)) return geometry::MapUniform(*u, lo, hi);
  return rng_.Uniform(lo, hi);
}

double Interpreter::DrawNormal(double mean, double std, SourceSpan span) {
  ++draws_;
  if (const double* u = TakeCoordinates(1, "Normal", span)) {
    return mean + std * geometry::MapNormal(*u);
  }
  return mean + std * rng_.Normal();
}

double Interpreter::DrawTruncatedNormal(double mean, double std, double lo, double hi,
                                        SourceSpan span, int max_tries) {
  ++draws_;
  if (const double* u = TakeCoordinates(1, "TruncatedNormal", span)) {
    const double x = geometry::MapTruncatedNormal(*u, mean, std, lo, hi);
    if (!std::isnan(x)) return x;
  }
  // The stream: a normal draw repeated until it lands in [lo, hi].
  for (int tries = 0; tries <= max_tries; ++tries) {
    const double x = mean + std * rng_.Normal();
    if (x >= lo && x <= hi) return x;
  }
  return NAN;
}

int64_t Interpreter::DrawInt(int64_t lo, int64_t hi, SourceSpan span, const char* draw) {
  ++draws_;
  if (const double* u = TakeCoordinates(1, draw, span)) return geometry::MapUniformInt(*u, lo, hi);
  return rng_.UniformInt(lo, hi);
}

Eigen::Vector3d Interpreter::DrawPosition(const geometry::RegionSampler& sampler, int index,
                                          SourceSpan span) {
  ++draws_;
  if (const double* u = TakeCoordinates(sampler.dimension(), "position", span, index)) {
    return sampler.SampleAt(u, rng_);
  }
  return sampler.Sample(rng_);
}

Eigen::Vector3d Interpreter::DrawUnionPosition(const geometry::UnionSampler& sampler, int index,
                                               SourceSpan span) {
  static const std::string kPiece = "position piece";
  // Without balls the first try is taken; with balls a point outside one restarts the whole
  // draw, piece included, which keeps the law uniform over the union (union.h).
  constexpr int kMaxBallRetries = 10000;
  for (int attempt = 0; attempt < kMaxBallRetries; ++attempt) {
    int piece = 0;
    if (sampler.num_pieces() > 1) {
      const NamingScope naming(*this, index, &kPiece);
      piece = sampler.PickPiece(DrawUniform(0, sampler.measure(), span, "position piece"));
    }
    const geometry::RegionSampler& s = sampler.piece_sampler(piece);
    if (!sampler.has_balls()) return sampler.ToWorld(DrawPosition(s, index, span));
    ++draws_;
    const double* u = TakeCoordinates(s.dimension(), "position", span, index);
    const Eigen::Vector3d p_L = u ? s.MapPolytopePart(u) : s.SamplePolytopePart(rng_);
    if (s.IsInBalls(p_L)) return sampler.ToWorld(p_L);
  }
  Reject(RejectionKind::kEmptyRegion, "no room for " + scene_.objects[index].DisplayName(index),
         span, "its region is too thin to sample: 10,000 points fell outside its balls");
}

}  // namespace prs::lang::internal
