// Distributions (drawn when evaluated, remembered for `resample`) and region constructors
// (turned into exact convex regions of the geometry core; its argument errors become located
// diagnostics).
#include <cmath>

#include "lang/interp_internal.h"

namespace prs::lang::internal {

using Eigen::Vector3d;
using geometry::ConvexRegion;

namespace {
constexpr int kMaxTruncatedNormalTries = 100000;
}

Value Interpreter::CallDistribution(Builtin id, const std::vector<Value>& args,
                                    const std::vector<SourceSpan>& spans, SourceSpan span) {
  auto number = [&](size_t i, const char* what) { return ToNumber(args[i], spans[i], what); };
  auto distribution = std::make_shared<Distribution>();
  switch (id) {
    case Builtin::kVector3D:
      return Value(Vector3d(number(0, "x"), number(1, "y"), number(2, "z")));
    case Builtin::kResample:
      return Resample(args[0], spans[0]);
    case Builtin::kRange:
    case Builtin::kDiscreteRange:
    case Builtin::kNormal:
      distribution->kind = id == Builtin::kRange           ? DistributionKind::kRange
                           : id == Builtin::kDiscreteRange ? DistributionKind::kDiscreteRange
                                                           : DistributionKind::kNormal;
      distribution->args = {number(0, "the first parameter"), number(1, "the second parameter")};
      // The converted numbers: a bound may be a boolean (True is 1).
      if (id == Builtin::kDiscreteRange) CheckWholeNumbers(distribution->args, spans);
      if (id == Builtin::kNormal && !(distribution->args[1].As<double>() >= 0)) {
        Fail(spans[1], "bad-value", "a normal's standard deviation must be >= 0, got " +
                                        FormatNumber(distribution->args[1].As<double>()));
      }
      break;
    case Builtin::kTruncatedNormal:
      distribution->kind = DistributionKind::kTruncatedNormal;
      for (size_t i = 0; i < 4; ++i) distribution->args.push_back(number(i, "each parameter"));
      break;
    case Builtin::kUniform:
    case Builtin::kOptions:
      distribution->kind = DistributionKind::kUniformChoice;
      distribution->args = id == Builtin::kUniform ? args : Iterate(args[0], spans[0]);
      if (distribution->args.empty()) Fail(span, "bad-value", "there is nothing to choose from");
      break;
    case Builtin::kDiscrete: {
      const auto* dict = std::get_if<std::shared_ptr<DictData>>(&args[0].data);
      if (!dict) Fail(spans[0], "type-error", "Discrete needs a dict {value: weight, ...}");
      double total = 0;
      for (const auto& [value, weight] : (*dict)->entries) {
        const double w = ToNumber(weight, spans[0], "each weight");
        if (!(w >= 0)) Fail(spans[0], "bad-value", "weights must not be negative");
        distribution->args.push_back(value);
        distribution->weights.push_back(w);
        total += w;
      }
      if (!(total > 0)) Fail(spans[0], "bad-value", "the weights of Discrete add up to zero");
      for (double& w : distribution->weights) w /= total;
      distribution->kind = DistributionKind::kDiscrete;
      break;
    }
    default:
      Fail(span, "internal", "not a distribution");
  }
  Value result = Draw(*distribution, span);
  result.origin = distribution;
  return result;
}

// DiscreteRange's bounds are integers; a fractional bound is almost surely a slip for Range.
void Interpreter::CheckWholeNumbers(const std::vector<Value>& args,
                                    const std::vector<SourceSpan>& spans) {
  for (size_t i = 0; i < 2; ++i) {
    const double x = args[i].As<double>();
    if (std::abs(x) > 9007199254740992.0) {  // 2^53: beyond it, not every integer exists
      Fail(spans[i], "bad-value", "DiscreteRange's bounds must be within ±2^53, got " +
                                      FormatNumber(x));
    }
    if (x != std::trunc(x)) {
      Fail(spans[i], "bad-value",
           "DiscreteRange's bounds must be whole numbers, got " + FormatNumber(x),
           {{{}, false, "use Range(low, high) for a real number in an interval"}});
    }
  }
}

// Draws one value from a distribution; the result remembers where it came from.
Value Interpreter::Draw(const Distribution& d, SourceSpan span) {
  auto arg = [&](size_t i) { return d.args[i].As<double>(); };
  Value result;
  switch (d.kind) {
    case DistributionKind::kRange:
      result = DrawUniform(std::min(arg(0), arg(1)), std::max(arg(0), arg(1)), span, "Range");
      break;
    case DistributionKind::kDiscreteRange: {
      const double lo = std::ceil(std::min(arg(0), arg(1))), hi = std::floor(std::max(arg(0), arg(1)));
      if (lo > hi) Fail(span, "bad-value", "DiscreteRange contains no integer");
      result = static_cast<double>(
          DrawInt(static_cast<int64_t>(lo), static_cast<int64_t>(hi), span, "DiscreteRange"));
      break;
    }
    case DistributionKind::kNormal:
      if (!(arg(1) >= 0)) Fail(span, "bad-value", "a normal's standard deviation must be >= 0");
      result = DrawNormal(arg(0), arg(1), span);
      break;
    case DistributionKind::kTruncatedNormal: {
      const double mean = arg(0), std = arg(1), lo = arg(2), hi = arg(3);
      if (!(std > 0) || !(lo < hi)) {
        Fail(span, "bad-value", "TruncatedNormal needs std > 0 and low < high");
      }
      const double x = DrawTruncatedNormal(mean, std, lo, hi, span, kMaxTruncatedNormalTries);
      if (std::isnan(x)) {
        Fail(span, "bad-value", "TruncatedNormal's interval [" + Repr(lo) + ", " + Repr(hi) +
                                    "] holds almost none of the normal's mass");
      }
      result = x;
      break;
    }
    case DistributionKind::kUniformChoice:
      result = d.args[DrawInt(0, static_cast<int64_t>(d.args.size()) - 1, span, "Uniform")];
      break;
    case DistributionKind::kDiscrete: {
      double u = DrawUniform(0, 1, span, "Discrete");
      size_t i = 0;
      while (i + 1 < d.weights.size() && u >= d.weights[i]) u -= d.weights[i++];
      result = d.args[i];
      break;
    }
  }
  return result;
}

Value Interpreter::Resample(const Value& v, SourceSpan span) {
  if (v.origin) {
    Value fresh = Draw(*v.origin, span);
    fresh.origin = v.origin;
    return fresh;
  }
  const auto* tuple = std::get_if<std::shared_ptr<TupleData>>(&v.data);
  if (tuple && (*tuple)->elements.size() == 2 && (*tuple)->elements[0].Is<double>() &&
      (*tuple)->elements[1].Is<double>()) {
    const double a = (*tuple)->elements[0].As<double>(), b = (*tuple)->elements[1].As<double>();
    return DrawUniform(std::min(a, b), std::max(a, b), span, "interval");
  }
  Fail(span, "bad-resample",
       "resample needs a value drawn from a distribution (Range, Normal, Uniform, ...), but this "
       "is a plain " + TypeName(v));
}

Value Interpreter::CallRegion(Builtin id, const std::vector<Value>& args,
                              const std::vector<SourceSpan>& spans, SourceSpan span) {
  auto number = [&](size_t i, const char* what) { return ToNumber(args[i], spans[i], what); };
  auto vector = [&](size_t i, const char* what) { return ToVector(args[i], spans[i], what); };
  auto rotation = [&](size_t i) {
    return ToOrientation(args[i], spans[i], "the orientation").toRotationMatrix();
  };
  auto nonnegative = [&](size_t i, const char* what) {
    const double x = number(i, what);
    if (!(x >= 0)) Fail(spans[i], "bad-value", std::string(what) + " must be >= 0, got " + Repr(x));
    return x;
  };
  try {
    ConvexRegion region = ConvexRegion::All();
    switch (id) {
      case Builtin::kCuboid:
        region = ConvexRegion::MakeCuboid(vector(0, "the centre"), rotation(1),
                                          nonnegative(2, "the width"), nonnegative(3, "the length"),
                                          nonnegative(4, "the height"));
        break;
      case Builtin::kRect3D:
        region = ConvexRegion::MakeRect3D(vector(2, "the origin"), rotation(3),
                                          nonnegative(0, "the width"), nonnegative(1, "the length"));
        break;
      case Builtin::kHalfSpace:
        region = ConvexRegion::MakeHalfSpace(vector(0, "the point"), vector(1, "the normal"));
        break;
      case Builtin::kSphere:
        region = ConvexRegion::MakeSphere(vector(0, "the centre"), nonnegative(1, "the radius"));
        break;
      case Builtin::kConvexPolygon3D: {
        std::vector<Vector3d> vertices;
        for (const Value& item : Iterate(args[0], spans[0])) {
          vertices.push_back(ToVector(item, spans[0], "each vertex"));
        }
        region = ConvexRegion::MakeConvexPolygon3D(vertices);
        break;
      }
      case Builtin::kConvexPolyhedron: {
        std::vector<geometry::HalfSpace> half_spaces;
        for (const Value& item : Iterate(args[0], spans[0])) {
          if (!item.Is<RegionPtr>()) {
            Fail(spans[0], "type-error", "ConvexPolyhedron needs a list of HalfSpace(point, normal)");
          }
          for (const auto& h : item.As<RegionPtr>()->half_spaces()) half_spaces.push_back(h);
        }
        region = ConvexRegion::MakeConvexPolyhedron(half_spaces);
        break;
      }
      case Builtin::kEmpty:
        region = ConvexRegion::Empty();
        break;
      default:
        break;
    }
    return RegionPtr(std::make_shared<ConvexRegion>(std::move(region)));
  } catch (const std::invalid_argument& e) {
    Fail(span, "bad-region", std::string(GetBuiltinInfo(id).name) + ": " + e.what());
  }
}

}  // namespace prs::lang::internal
