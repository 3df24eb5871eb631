// Calls: user functions (with the call-depth limit), built-in helpers, the math module,
// vector and region methods. Distributions and region constructors are in call_random.cc.
#include <bit>
#include <cmath>
#include <optional>

#include "lang/interp_internal.h"

namespace prs::lang::internal {

using Eigen::Vector3d;

namespace {

bool IsRegionConstructor(Builtin id) { return id >= Builtin::kCuboid && id <= Builtin::kEmpty; }

}  // namespace

Value Interpreter::EvalCall(const CallExpr& call, SourceSpan span) {
  const Value callee = Eval(*call.callee);
  std::vector<Value> args;
  std::vector<SourceSpan> spans;
  EvalArguments(call, args, spans);
  if (const auto* builtin = std::get_if<BuiltinRef>(&callee.data)) {
    CheckArgumentCount(builtin->id, static_cast<int>(args.size()), span);
    if (options_.cache && IsRegionConstructor(builtin->id)) {
      return CallRegionKept(call, builtin->id, args, spans, span);
    }
    return CallBuiltin(builtin->id, args, spans, span);
  }
  if (const auto* fn = std::get_if<FunctionRef>(&callee.data)) {
    return CallFunction(*fn, call, std::move(args), span);
  }
  if (const auto* method = std::get_if<BoundMethod>(&callee.data)) {
    return CallMethod(*method, args, spans, span);
  }
  if (callee.Is<const ClassInfo*>()) {
    Fail(call.callee->span, "type-error",
         "classes are not called like functions; create an object with '" +
             callee.As<const ClassInfo*>()->name + " with PROP VALUE, at V, on X, ...'");
  }
  Fail(call.callee->span, "type-error", "a " + TypeName(callee) + " cannot be called");
}

void Interpreter::EvalArguments(const CallExpr& call, std::vector<Value>& args,
                                std::vector<SourceSpan>& spans) {
  args.reserve(call.args.size());
  spans.reserve(call.args.size());
  for (const CallArg& arg : call.args) {
    args.push_back(Eval(*arg.value));
    spans.push_back(arg.value->span);
  }
}

void Interpreter::CheckArgumentCount(Builtin id, int n, SourceSpan span) {
  const BuiltinInfo& info = GetBuiltinInfo(id);
  if (n < info.min_args || (info.max_args >= 0 && n > info.max_args) ||
      (id == Builtin::kSphere && n == 1)) {
    Fail(span, "wrong-argument-count",
         std::string(info.name) + " was given " + std::to_string(n) + " arguments; call it as " +
             info.signature);
  }
}

std::optional<Interpreter::NumberRange> Interpreter::EvalRangeCall(const Expr& expr) {
  const auto* call = std::get_if<CallExpr>(&expr.node);
  if (!call) return std::nullopt;
  const auto* name = std::get_if<NameRef>(&call->callee->node);
  if (!name) return std::nullopt;
  const Value callee = Lookup(name->name, call->callee->span);
  const auto* builtin = std::get_if<BuiltinRef>(&callee.data);
  if (!builtin || builtin->id != Builtin::kRangeFn) return std::nullopt;
  EnterNested(expr.span);  // as Eval of the call would
  std::vector<Value> args;
  std::vector<SourceSpan> spans;
  EvalArguments(*call, args, spans);
  CheckArgumentCount(Builtin::kRangeFn, static_cast<int>(args.size()), expr.span);
  const NumberRange range = CalcRange(args, spans, expr.span);
  --eval_depth_;
  return range;
}

Interpreter::NumberRange Interpreter::CalcRange(const std::vector<Value>& args,
                                                const std::vector<SourceSpan>& spans,
                                                SourceSpan span) {
  auto number = [&](size_t i, const char* what) { return ToNumber(args[i], spans[i], what); };
  double start = 0, stop = number(0, "range's stop"), step = 1;
  if (args.size() >= 2) start = stop, stop = number(1, "range's stop");
  if (args.size() == 3) step = number(2, "range's step");
  if (step == 0) Fail(span, "bad-value", "range's step must not be zero");
  const double count = std::max(0.0, std::ceil((stop - start) / step));
  if (count > static_cast<double>(options_.limits.max_loop_iterations)) {
    Fail(span, "limit-exceeded",
         "range of " + Repr(count) + " numbers is longer than the loop limit of one scene");
  }
  return {start, step, static_cast<int64_t>(count)};
}

namespace {

// The bits of plain arguments (numbers, vectors, orientations), each after a tag for its type;
// false for any other argument.
bool AppendArgumentBits(const std::vector<Value>& args, std::vector<uint64_t>& bits) {
  auto append = [&](double x) { bits.push_back(std::bit_cast<uint64_t>(x)); };
  for (const Value& arg : args) {
    if (const auto* x = std::get_if<double>(&arg.data)) {
      bits.push_back(0);
      append(*x);
    } else if (const auto* v = std::get_if<Vector3d>(&arg.data)) {
      bits.push_back(1);
      for (int i = 0; i < 3; ++i) append((*v)[i]);
    } else if (const auto* o = std::get_if<Orientation>(&arg.data)) {
      bits.push_back(2);
      for (const double c : o->R_WF.coeffs()) append(c);
    } else {
      return false;
    }
  }
  return true;
}

}  // namespace

Value Interpreter::CallRegionKept(const CallExpr& call, Builtin id, const std::vector<Value>& args,
                                  const std::vector<SourceSpan>& spans, SourceSpan span) {
  std::vector<uint64_t> bits;
  if (!AppendArgumentBits(args, bits)) return CallBuiltin(id, args, spans, span);
  RunCache& cache = *options_.cache;
  const auto found = cache.region_calls.find(&call);
  if (found != cache.region_calls.end()) {
    RunCache::RegionCall& kept = found->second;
    if (!kept.varying && kept.argument_bits == bits) return kept.region;
    kept.varying = true;
    return CallBuiltin(id, args, spans, span);
  }
  Value region = CallBuiltin(id, args, spans, span);  // may throw: nothing is kept then
  if (region.Is<RegionPtr>()) {
    // Later scenes share it, and scenes carry it to other threads (Scene::workspace): its
    // lazily computed form is filled now, so that reading it there races with nothing.
    region.As<RegionPtr>()->Finalize();
    cache.kept_regions.insert(region.As<RegionPtr>().get());
    cache.region_calls.emplace(&call,
                               RunCache::RegionCall{std::move(bits), region.As<RegionPtr>()});
  }
  return region;
}

Value Interpreter::CallFunction(const FunctionRef& fn, const CallExpr& call,
                                std::vector<Value> args, SourceSpan span) {
  if (call_depth_ >= options_.limits.max_call_depth) {
    Fail(span, "limit-exceeded",
         "function calls nested deeper than " + std::to_string(options_.limits.max_call_depth) +
             "; is this recursion meant to end?");
  }
  Env frame;
  const auto& params = fn.def->params;
  size_t positional = 0;
  for (size_t i = 0; i < call.args.size(); ++i) {
    if (call.args[i].keyword) {
      frame[call.args[i].keyword->name] = args[i];
    } else if (positional < params.size()) {
      frame[params[positional++].name.name] = args[i];
    } else {
      Fail(span, "wrong-argument-count", "too many arguments for '" + fn.def->name.name + "'");
    }
  }
  Env* saved_locals = locals_;
  const int saved_module = current_module_;
  current_module_ = fn.module_index;
  for (const Param& p : params) {
    if (frame.count(p.name.name)) continue;
    if (!p.default_value) {
      Fail(span, "wrong-argument-count",
           "'" + fn.def->name.name + "' needs a value for '" + p.name.name + "'");
    }
    locals_ = saved_locals;  // defaults are evaluated where the function was defined
    frame[p.name.name] = Eval(*p.default_value);
  }
  locals_ = &frame;
  ++call_depth_;
  const Flow flow = ExecBody(fn.def->body);
  --call_depth_;
  locals_ = saved_locals;
  current_module_ = saved_module;
  Value result = flow == Flow::kReturn ? std::move(return_value_) : Value();
  return_value_ = Value();
  return result;
}

Value Interpreter::CallBuiltin(Builtin id, const std::vector<Value>& args,
                               const std::vector<SourceSpan>& spans, SourceSpan span) {
  if (id >= Builtin::kSin) return CallMath(id, args, spans, span);
  if (id == Builtin::kSphere && args.empty()) return PrimitiveRef{shapes::Primitive::kSphere};
  if (IsRegionConstructor(id)) return CallRegion(id, args, spans, span);
  if (id < Builtin::kCuboid) return CallDistribution(id, args, spans, span);
  auto number = [&](size_t i, const char* what) { return ToNumber(args[i], spans[i], what); };
  switch (id) {
    case Builtin::kRangeFn: {
      const NumberRange range = CalcRange(args, spans, span);
      auto list = std::make_shared<ListData>();  // numbers only: depth 1
      list->elements.reserve(static_cast<size_t>(range.count));
      for (int64_t i = 0; i < range.count; ++i) list->elements.emplace_back(range.At(i));
      return Value(std::move(list));
    }
    case Builtin::kLen: return static_cast<double>(Iterate(args[0], spans[0]).size());
    case Builtin::kAbs:
      if (args[0].Is<Vector3d>()) return Value(Vector3d(args[0].As<Vector3d>().cwiseAbs()));
      return std::fabs(number(0, "abs's argument"));
    case Builtin::kMin:
    case Builtin::kMax: {
      std::vector<Value> items = args.size() == 1 ? Iterate(args[0], spans[0]) : args;
      if (items.empty()) Fail(span, "bad-value", "min() and max() need at least one value");
      double best = ToNumber(items[0], span, "each value");
      for (const Value& item : items) {
        const double x = ToNumber(item, span, "each value");
        best = id == Builtin::kMin ? std::min(best, x) : std::max(best, x);
      }
      return best;
    }
    case Builtin::kRound: {
      const double scale = args.size() == 2 ? std::pow(10.0, number(1, "the digits")) : 1.0;
      return std::nearbyint(number(0, "round's argument") * scale) / scale;
    }
    case Builtin::kInt: return std::trunc(number(0, "int's argument"));
    case Builtin::kFloat: return number(0, "float's argument");
    case Builtin::kStr: return args[0].Is<StringPtr>() ? args[0] : MakeString(Repr(args[0]));
    case Builtin::kBool: return Truthy(args[0], spans[0]);
    case Builtin::kList: return MakeList(Iterate(args[0], spans[0]));
    case Builtin::kSum: {
      double total = 0;
      for (const Value& item : Iterate(args[0], spans[0])) total += ToNumber(item, spans[0], "each value");
      return total;
    }
    case Builtin::kMesh: return CallMesh(args, spans, span);
    case Builtin::kCylinder: return PrimitiveRef{shapes::Primitive::kCylinder};
    case Builtin::kCapsule: return PrimitiveRef{shapes::Primitive::kCapsule};
    default: break;
  }
  Fail(span, "internal", "built-in not implemented");
}

Value Interpreter::CallMath(Builtin id, const std::vector<Value>& args,
                            const std::vector<SourceSpan>& spans, SourceSpan span) {
  const double x = ToNumber(args[0], spans[0], "the argument");
  const double y = args.size() > 1 ? ToNumber(args[1], spans[1], "the second argument") : 0;
  double r = 0;
  switch (id) {
    case Builtin::kSin: r = std::sin(x); break;
    case Builtin::kCos: r = std::cos(x); break;
    case Builtin::kTan: r = std::tan(x); break;
    case Builtin::kAsin: r = std::asin(x); break;
    case Builtin::kAcos: r = std::acos(x); break;
    case Builtin::kAtan: r = std::atan(x); break;
    case Builtin::kAtan2: r = std::atan2(x, y); break;
    case Builtin::kSqrt: r = std::sqrt(x); break;
    case Builtin::kExp: r = std::exp(x); break;
    case Builtin::kLog: r = args.size() > 1 ? std::log(x) / std::log(y) : std::log(x); break;
    case Builtin::kRadians: r = x * M_PI / 180; break;
    case Builtin::kDegrees: r = x * 180 / M_PI; break;
    case Builtin::kFloor: r = std::floor(x); break;
    case Builtin::kCeil: r = std::ceil(x); break;
    case Builtin::kFabs: r = std::fabs(x); break;
    case Builtin::kHypot: r = std::hypot(x, y); break;
    default: break;
  }
  if (!std::isfinite(r)) {
    Fail(span, "bad-value", std::string(GetBuiltinInfo(id).name) + " of " + Repr(args[0]) +
                                " is not a finite number (outside the function's domain)");
  }
  return r;
}

Value Interpreter::CallMethod(const BoundMethod& method, const std::vector<Value>& args,
                              const std::vector<SourceSpan>& spans, SourceSpan span) {
  const Value& receiver = *method.receiver;
  const size_t want = (method.name == "norm" || method.name == "normalized") ? 0 : 1;
  if (args.size() != want) {
    Fail(span, "wrong-argument-count", "'" + method.name + "' takes " + std::to_string(want) +
                                           " argument" + (want == 1 ? "" : "s"));
  }
  if (const auto* v = std::get_if<Vector3d>(&receiver.data)) {
    if (method.name == "norm") return v->norm();
    if (method.name == "normalized") {
      if (v->norm() < 1e-12) Fail(span, "bad-value", "cannot normalize a zero vector");
      return Value(Vector3d(v->normalized()));
    }
    const Vector3d other = ToVector(args[0], spans[0], "the argument");
    if (method.name == "dot") return v->dot(other);
    return Value(Vector3d(v->cross(other)));
  }
  const auto& region = receiver.As<RegionPtr>();
  if (method.name == "contains") {
    if (const auto* object = std::get_if<ObjectRef>(&args[0].data)) {
      if (scene_.objects[object->index].cls->has_box) {
        return RegionContainsObject(*region, object->index, geometry::kGeometricTolerance);
      }
    }
    return region->Contains(ToVector(args[0], spans[0], "the argument of 'contains'"));
  }
  if (!args[0].Is<RegionPtr>()) {
    Fail(spans[0], "type-error", "'intersect' needs a region, but this is a " + TypeName(args[0]));
  }
  return RegionPtr(std::make_shared<geometry::ConvexRegion>(
      geometry::Intersect(*region, *args[0].As<RegionPtr>())));
}

}  // namespace prs::lang::internal
