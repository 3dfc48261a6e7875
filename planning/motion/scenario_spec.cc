#include "planning/motion/scenario_spec.h"

#include <algorithm>
#include <filesystem>
#include <limits>
#include <stdexcept>

#include "base/json_reader.h"
#include "base/str_cat.h"

namespace planning {

inline constexpr base::EnumName<SweepMode> kSweepModeNames[] = {
    {SweepMode::kForwardly, "forwardly"},
    {SweepMode::kSymmetric, "symmetric"},
    {SweepMode::kLocalGaussNewton, "local_gauss_newton"},
};
constexpr std::span<const base::EnumName<SweepMode>> EnumNames(SweepMode) {
  return kSweepModeNames;
}

inline constexpr base::EnumName<WritheOutput> kWritheOutputNames[] = {
    {WritheOutput::kMatrix, "matrix"},
    {WritheOutput::kTotal, "total"},
};
constexpr std::span<const base::EnumName<WritheOutput>> EnumNames(WritheOutput) {
  return kWritheOutputNames;
}

inline constexpr base::EnumName<FinalPoseInit> kFinalPoseInitNames[] = {
    {FinalPoseInit::kStart, "start"},
    {FinalPoseInit::kUnwrapped, "unwrapped"},
    {FinalPoseInit::kIk, "ik"},
};
constexpr std::span<const base::EnumName<FinalPoseInit>> EnumNames(FinalPoseInit) {
  return kFinalPoseInitNames;
}

namespace {

// Value limits checked where each number is read (documented in scenario_spec.h).
constexpr double kMaxLength = 10.0;              // radii, margins, tolerances (m or rad)
constexpr double kMaxWeight = 1e12;              // precisions, rates, damping, priors
constexpr double kMinResolution = 1e-6;          // edge-check resolutions (rad)
constexpr int kMaxIterations = 100000;           // AICO sweeps and roll-out iterations
constexpr std::int64_t kMaxChecks = 1000000000;  // RRT collision-check budget

namespace fs = std::filesystem;

// The enum named by a string node; the error (with the JSON path) lists the valid names.
template <typename E>
E Parse(const base::JsonNode& n, const std::string& what) {
  return base::Located(n, [&] { return base::ParseEnum<E>(n.String(), what); });
}

SpecName Name(const base::JsonNode& n) { return {n.String(), n.Where()}; }

SpecName Name(const base::JsonNode& n, const std::string& key) { return Name(n.At(key)); }

// n[key]: "open" (also when absent) -> false, "chord" -> true; anything else is an error.
bool ParseClosure(const base::JsonNode& n, const char* key) {
  const std::string closure = n.String(key, "open");
  if (closure != "open" && closure != "chord") {
    throw std::invalid_argument(
        base::StrCat(n.Where(), ".", key, ": \"", closure, "\" is not \"open\" or \"chord\""));
  }
  return closure == "chord";
}

// The names of the objects read so far, in file order.
using NameList = std::vector<std::string>;

// "frame" of `n` when given: the name of one of `objects` (the objects `before` it in the file,
// or all of them), else an error naming the key.
std::optional<SpecName> ReadFrame(const base::JsonNode& n, const NameList& objects,
                                  bool before = false) {
  if (!n.Has("frame")) return std::nullopt;
  const base::JsonNode fn = n.At("frame");
  SpecName name = Name(fn);
  if (std::find(objects.begin(), objects.end(), name.name) == objects.end()) {
    std::string list;
    for (const std::string& o : objects) list.append(list.empty() ? "" : ", ").append(o);
    fn.Fail(base::StrCat("unknown object '", name.name, "' (objects", before ? " before it" : "",
                         ": ", list.empty() ? "none" : list, ")",
                         base::DidYouMean(name.name, objects)));
  }
  return name;
}

ObjectSpec ReadObject(const base::JsonNode& n, const std::string& dir,
                      const std::vector<std::string>& roots, const NameList& earlier) {
  n.CheckKeys({"name", "urdf", "xyz", "rpy", "collide", "capsules", "frame"});
  ObjectSpec o;
  o.where = n.Where();
  o.name = n.At("name").String();
  const base::JsonNode un = n.At("urdf");
  o.urdf = ResolveDataFile(un.String(), dir, roots, un.Where());
  o.xyz = n.Vec3("xyz", o.xyz);
  o.rpy = n.Vec3("rpy", o.rpy);
  o.collide = n.Bool("collide", true);
  o.frame = ReadFrame(n, earlier, /*before=*/true);
  if (n.Has("capsules")) {
    const base::JsonNode cn = n.At("capsules");
    cn.CheckKeys({"chain", "radius"});
    o.capsule_chain = Name(cn, "chain");
    o.capsule_radius = cn.At("radius").Number(0.0, kMaxLength);
    if (!(o.capsule_radius > 0)) cn.At("radius").Fail("expected a positive radius");
  }
  return o;
}

CollisionSpec ReadCollision(const base::JsonNode& n) {
  n.CheckKeys({"self", "disabled_pairs", "disabled_groups", "analytic_capsules"});
  CollisionSpec c;
  c.where = n.Where();
  c.self = n.Bool("self", true);
  c.analytic_capsules = n.Bool("analytic_capsules", false);
  if (n.Has("disabled_pairs")) {
    const base::JsonNode dp = n.At("disabled_pairs");
    for (size_t i = 0; i < dp.Size(); ++i) {
      const base::JsonNode pn = dp.At(i);
      if (pn.Size() != 2) pn.Fail("expected [link_a, link_b]");
      c.disabled_pairs.emplace_back(pn.At(0).String(), pn.At(1).String());
    }
  }
  if (n.Has("disabled_groups")) {
    const base::JsonNode gs = n.At("disabled_groups");
    for (size_t g = 0; g < gs.Size(); ++g) c.disabled_groups.push_back(gs.At(g).Strings());
    c.groups_where = gs.Where();
  }
  return c;
}

StartSpec ReadStart(const base::JsonNode& n) {
  n.CheckKeys({"q", "coil", "pose"});
  StartSpec s;
  s.where = n.Where();
  if (n.Has("q") + n.Has("coil") + n.Has("pose") != 1) {
    n.Fail("expected exactly one of \"q\", \"coil\" or \"pose\"");
  }
  if (n.Has("pose")) {
    s.kind = StartKind::kPose;
    s.where = n.At("pose").Where();
    s.pose = n.At("pose").String();
    return s;
  }
  if (n.Has("q")) {
    const base::JsonNode qn = n.At("q");
    s.where = qn.Where();
    if (qn.IsString()) {
      if (qn.String() != "zero") qn.Fail("expected \"zero\" or a configuration");
      s.kind = StartKind::kZero;
    } else {
      s.kind = StartKind::kQ;
      s.q = qn.Vector();
    }
    return s;
  }
  const base::JsonNode cn = n.At("coil");
  cn.CheckKeys({"wrap_deg", "step", "margin"});
  s.kind = StartKind::kCoil;
  s.where = cn.Where();
  s.wrap_deg = cn.Number("wrap_deg", s.wrap_deg);
  if (!(s.wrap_deg >= 0.0 && s.wrap_deg <= 2000.0)) cn.Fail("wrap_deg must be in [0, 2000]");
  s.step = cn.Number("step", s.step, 1e-3, 10.0);
  s.margin = cn.Number("margin", s.margin, 0.0, kMaxLength);
  return s;
}

ProblemSpec ReadProblem(const base::JsonNode& n) {
  n.CheckKeys({"T", "duration", "dynamic", "h_rate", "w_rate", "q_rate"});
  ProblemSpec p;
  if (n.Has("T")) p.num_steps = static_cast<int>(n.At("T").Integer(1, 10000));
  p.duration = n.Number("duration", p.duration, 1e-3, 1e4);
  p.dynamic = n.Bool("dynamic", p.dynamic);
  p.h_rate = n.Number("h_rate", p.h_rate, 1e-12, kMaxWeight);
  p.w_rate = n.Number("w_rate", p.w_rate, 1e-12, kMaxWeight);
  p.q_rate = n.Number("q_rate", p.q_rate, 0.0, kMaxWeight);
  return p;
}

FeatureSpec ReadFeature(const base::JsonNode& n, const NameList& objects) {
  FeatureSpec f;
  f.where = n.Where();
  f.type = Parse<FeatureType>(n.At("type"), "feature type");
  switch (f.type) {
    case FeatureType::kPosition:
      n.CheckKeys({"type", "link", "offset"});
      f.link = Name(n, "link");
      f.offset = n.Vec3("offset", f.offset);
      break;
    case FeatureType::kAxisAlignment:
      n.CheckKeys({"type", "link", "axis", "direction", "frame"});
      f.link = Name(n, "link");
      f.axis = n.Vec3("axis", f.axis);
      f.direction = n.At("direction").Vec3();
      f.frame = ReadFrame(n, objects);
      break;
    case FeatureType::kJointLimits:
      n.CheckKeys({"type", "margin", "prismatic_margin"});
      f.margin = n.Number("margin", 0.0);
      f.prismatic_margin = n.Number("prismatic_margin", 0.0);
      break;
    case FeatureType::kJointPosition:
      n.CheckKeys({"type"});
      break;
    case FeatureType::kBox:
      n.CheckKeys({"type", "link", "offset", "center", "half_extent", "margin", "frame"});
      f.link = Name(n, "link");
      f.offset = n.Vec3("offset", f.offset);
      f.center = n.At("center").Vec3();
      f.frame = ReadFrame(n, objects);
      f.half_extent = n.At("half_extent").Vec3();
      f.margin = n.Number("margin", 0.0);
      break;
    case FeatureType::kWrithe:
      n.CheckKeys({"type", "chain", "object", "object_chain", "output", "closure"});
      f.chain = Name(n, "chain");
      f.object = Name(n, "object");
      f.object_chain = Name(n, "object_chain");
      if (n.Has("output")) f.output = Parse<WritheOutput>(n.At("output"), "writhe output");
      f.closed_by_chord = ParseClosure(n, "closure");
      break;
    case FeatureType::kWinding:
      n.CheckKeys(
          {"type", "chain", "axis_point", "axis_direction", "object", "object_chain", "frame"});
      f.chain = Name(n, "chain");
      if (n.Has("object") || n.Has("object_chain")) {
        if (n.Has("axis_point") || n.Has("axis_direction"))
          n.Fail("give either axis_point and axis_direction or object and object_chain");
        if (n.Has("frame")) n.At("frame").Fail("\"frame\" is for axis_point and axis_direction");
        f.object = Name(n, "object");
        f.object_chain = Name(n, "object_chain");
      } else {
        f.axis_point = n.At("axis_point").Vec3();
        f.axis_direction = n.At("axis_direction").Vec3();
        f.frame = ReadFrame(n, objects);
      }
      break;
    case FeatureType::kCollision:
      n.CheckKeys({"type", "margin"});
      f.margin = n.Number("margin", 0.05);
      break;
    case FeatureType::kLineClearance:
      n.CheckKeys({"type", "chain", "object", "object_chain", "margin"});
      f.chain = Name(n, "chain");
      f.object = Name(n, "object");
      f.object_chain = Name(n, "object_chain");
      f.margin = n.Number("margin", 0.05);
      break;
  }
  return f;
}

TaskSpec ReadTask(const base::JsonNode& n, const NameList& objects) {
  n.CheckKeys({"name", "feature", "order", "between", "max_jump", "target", "precision",
               "final_precision", "final_steps"});
  TaskSpec t;
  t.where = n.Where();
  t.name = n.String("name", t.name);
  t.feature = ReadFeature(n.At("feature"), objects);
  if (n.Has("order")) t.order = static_cast<int>(n.At("order").Integer(0, 1));
  if (n.Has("between")) t.between = static_cast<int>(n.At("between").Integer(0, 64));
  if (t.between > 0 && t.order != 0) n.Fail("\"between\" needs an order-0 task");
  t.max_jump = n.Number("max_jump", 0.0, 0.0, kMaxWeight);
  if (t.max_jump > 0 && t.order != 0) n.Fail("\"max_jump\" needs an order-0 task");
  t.precision = n.Number("precision", 0.0, 0.0, kMaxWeight);
  t.final_precision = n.Number("final_precision", t.precision, 0.0, kMaxWeight);
  if (t.precision < 0 || t.final_precision < 0) n.Fail("precisions must be >= 0");
  if (n.Has("final_steps")) {
    t.final_steps = static_cast<int>(n.At("final_steps").Integer(1, 10000));
    t.final_steps_where = n.Where() + ".final_steps";
  }
  t.target.where = n.Where() + ".target";
  if (n.Has("target")) {
    const base::JsonNode tn = n.At("target");
    tn.CheckKeys({"type", "value", "reach_at", "frame", "chord_to"});
    t.target.kind =
        tn.Has("type") ? Parse<TargetKind>(tn.At("type"), "target type") : TargetKind::kValue;
    if (tn.Has("reach_at")) {
      if (t.target.kind != TargetKind::kInterpolate && t.target.kind != TargetKind::kFinalPose)
        tn.Fail("\"reach_at\" needs an \"interpolate\" or \"final_pose\" target");
      t.target.reach_at = tn.At("reach_at").Number(1e-6, 1.0);
    }
    if (t.target.kind == TargetKind::kValue || t.target.kind == TargetKind::kInterpolate) {
      const base::JsonNode vn = tn.At("value");
      t.target.value_where = vn.Where();
      t.target.scalar = vn.IsNumber();
      t.target.value = vn.IsNumber() ? Eigen::VectorXd::Constant(1, vn.Number()) : vn.Vector();
    }
    if (tn.Has("chord_to")) {
      t.target.chord_to = Name(tn, "chord_to");
      if (t.target.kind != TargetKind::kInterpolate)
        tn.At("chord_to").Fail("\"chord_to\" needs an \"interpolate\" target");
      if (t.feature.type != FeatureType::kWrithe || t.feature.output != WritheOutput::kTotal)
        tn.At("chord_to").Fail("\"chord_to\" needs a \"writhe\" feature with output \"total\"");
      if (t.feature.closed_by_chord)  // the closed feature already contains the chord's writhe
        tn.At("chord_to").Fail("\"chord_to\" needs the open writhe (no \"closure\": \"chord\")");
    }
    t.target.frame = ReadFrame(tn, objects);
    if (t.target.frame) {
      const base::JsonNode fn = tn.At("frame");
      if (t.target.kind != TargetKind::kValue && t.target.kind != TargetKind::kInterpolate)
        fn.Fail("\"frame\" needs a \"value\" or \"interpolate\" target");
      if (t.feature.type != FeatureType::kPosition)
        fn.Fail("\"frame\" needs a \"position\" feature (a point target)");
      if (t.target.scalar || t.target.value.size() != 3)
        fn.Fail("\"frame\" needs a point value [x, y, z]");
    }
  }
  return t;
}

FinalPoseSpec ReadFinalPose(const base::JsonNode& n) {
  n.CheckKeys({"tasks", "alpha", "prior_scale", "init"});
  FinalPoseSpec f;
  const base::JsonNode ln = n.At("tasks");
  for (size_t i = 0; i < ln.Size(); ++i) f.tasks.push_back(Name(ln.At(i)));
  f.options.alpha = n.Number("alpha", f.options.alpha);
  f.options.prior_scale = n.Number("prior_scale", f.options.prior_scale);
  if (n.Has("init")) {
    const base::JsonNode in = n.At("init");
    f.init_where = in.Where();
    if (in.IsArray()) {
      f.init = FinalPoseInit::kQ;
      f.init_q = in.Vector();
    } else {
      f.init = Parse<FinalPoseInit>(in, "final-pose init (or a configuration)");
    }
  } else {
    f.init = FinalPoseInit::kIk;
  }
  return f;
}

SuccessSpec ReadSuccess(const base::JsonNode& n) {
  n.CheckKeys({"writhe_total_below", "writhe_closure", "position", "inside_box", "winding",
               "through_loop"});
  SuccessSpec s;
  s.writhe_total_below = n.Number("writhe_total_below", -1.0);
  s.writhe_closed_by_chord = ParseClosure(n, "writhe_closure");
  if (n.Has("position")) {
    const base::JsonNode pn = n.At("position");
    pn.CheckKeys({"task", "tolerance"});
    s.position_task = Name(pn, "task");
    s.position_tolerance = pn.Number("tolerance", s.position_tolerance, 0.0, kMaxLength);
  }
  if (n.Has("inside_box")) s.box_task = Name(n, "inside_box");
  if (n.Has("through_loop")) {
    s.through_loop = n.Bool("through_loop", false);
    s.through_loop_where = n.At("through_loop").Where();
  }
  if (n.Has("winding")) {
    const base::JsonNode wn = n.At("winding");
    wn.CheckKeys({"max_jump", "final_below", "final_closure", "tunnel"});
    s.winding_where = wn.Where();
    s.winding_max_jump = wn.Number("max_jump", 0.1);
    s.winding_final_below = wn.Number("final_below", 0.1);
    s.winding_closed_by_chord = ParseClosure(wn, "final_closure");
    const std::string tunnel = wn.String("tunnel", "line");
    if (tunnel != "line" && tunnel != "object") {
      throw std::invalid_argument(
          base::StrCat(wn.Where(), ".tunnel: \"", tunnel, "\" is not \"line\" or \"object\""));
    }
    s.winding_tunnel_through_object_only = tunnel == "object";
    if (!(s.winding_max_jump > 0.0) || !(s.winding_final_below > 0.0)) {
      throw std::invalid_argument(s.winding_where + ": max_jump and final_below must be > 0");
    }
  }
  return s;
}

// One "aico.retry" entry; its iteration limit defaults to aico.max_iterations (`a`).
AicoAttemptSpec ReadAicoRetry(const base::JsonNode& rn, const AicoOptions& a) {
  rn.CheckKeys({"precision_scale", "max_iterations", "init"});
  AicoAttemptSpec retry;
  retry.max_iterations = a.max_iterations;
  if (rn.Has("max_iterations")) {
    retry.max_iterations = static_cast<int>(rn.At("max_iterations").Integer(1, kMaxIterations));
  }
  if (rn.Has("precision_scale")) {
    const base::JsonNode sc = rn.At("precision_scale");
    if (!sc.IsObject()) sc.Fail("expected {\"task name\": factor, ...}");
    for (const auto& [task, fn] : sc.Members()) {
      const double f = fn.Number(0.0, kMaxWeight);
      if (!(f > 0.0)) fn.Fail("expected a positive factor");
      retry.precision_scale.push_back({{task, fn.Where()}, f});
    }
  }
  if (rn.Has("init")) {
    const base::JsonNode in = rn.At("init");
    retry.init = Parse<AicoInit>(in, "AICO init");
    retry.init_where = in.Where();
  }
  return retry;
}

void ReadAico(const base::JsonNode& n, ScenarioSpec* spec) {
  n.CheckKeys({"max_iterations", "tolerance", "damping", "sweep_mode", "max_step",
               "max_relocations", "relocation_damping", "rollout_init", "rollout_prior",
               "rollout_iterations", "stop_when_solved", "retry"});
  AicoOptions& a = spec->aico;
  const int kMax = kMaxIterations;
  if (n.Has("max_iterations"))
    a.max_iterations = static_cast<int>(n.At("max_iterations").Integer(1, kMax));
  a.tolerance = n.Number("tolerance", a.tolerance, 1e-12, 1e6);
  a.damping = n.Number("damping", a.damping, 0.0, kMaxWeight);
  if (n.Has("sweep_mode")) a.sweep_mode = Parse<SweepMode>(n.At("sweep_mode"), "sweep mode");
  a.max_step = n.Number("max_step", a.max_step, 1e-9, 1e3);
  if (n.Has("max_relocations")) {
    a.max_relocations = static_cast<int>(n.At("max_relocations").Integer(1, 100));
  }
  a.relocation_damping = n.Number("relocation_damping", a.relocation_damping, 1e-6, 1.0);
  a.rollout_init = n.Bool("rollout_init", a.rollout_init);
  a.rollout_prior = n.Number("rollout_prior", a.rollout_prior, 0.0, kMaxWeight);
  if (n.Has("rollout_iterations")) {
    a.rollout_iterations = static_cast<int>(n.At("rollout_iterations").Integer(1, kMax));
  }
  spec->aico_stop_when_solved = n.Bool("stop_when_solved", spec->aico_stop_when_solved);
  spec->aico_attempts[0].max_iterations = a.max_iterations;
  if (!n.Has("retry")) return;
  const base::JsonNode r = n.At("retry");
  if (!r.IsArray() && !r.IsObject()) r.Fail("expected an object or an array of objects");
  if (!r.IsArray()) {
    spec->aico_attempts.push_back(ReadAicoRetry(r, a));
    return;
  }
  if (r.Size() == 0) r.Fail("expected at least one retry");
  for (size_t i = 0; i < r.Size(); ++i) spec->aico_attempts.push_back(ReadAicoRetry(r.At(i), a));
}

RrtOptions ReadRrt(const base::JsonNode& n, ScenarioSpec* spec) {
  n.CheckKeys({"range", "resolution", "goal_bias", "max_checks", "goal_states",
               "goal_ik_iterations", "goal_ik_starts"});
  RrtOptions r;
  r.range = n.Number("range", r.range, 0.0, 1e3);
  r.resolution = n.Number("resolution", r.resolution, 0.0, 1e3);
  if (r.resolution > 0.0 && r.resolution < kMinResolution) {
    n.At("resolution").Fail("must be 0 (the default) or >= 1e-06 rad");
  }
  r.goal_bias = n.Number("goal_bias", r.goal_bias, 0.0, 1.0);
  if (n.Has("max_checks")) r.max_checks = n.At("max_checks").Integer(1, kMaxChecks);
  const auto integer = [&n](const char* key, int lo, int hi, int* value) {
    if (n.Has(key)) *value = static_cast<int>(n.At(key).Integer(lo, hi));
  };
  integer("goal_states", 1, 10000, &spec->rrt_goal.max_goal_states);
  integer("goal_ik_iterations", 1, 100000, &spec->rrt_goal.ik_iterations);
  integer("goal_ik_starts", 1, 100, &spec->rrt_goal.ik_starts);
  return r;
}

}  // namespace

std::string ResolveDataFile(const std::string& file, const std::string& base_dir,
                            const std::vector<std::string>& search_roots,
                            const std::string& where) {
  const fs::path p(file);
  if (p.is_absolute()) {
    if (!fs::exists(p)) throw std::invalid_argument(where + ": cannot find '" + file + "'");
    return file;
  }
  std::vector<std::string> tried = {(fs::path(base_dir) / p).lexically_normal().string()};
  fs::path stripped;  // without leading ".." segments
  bool leading = true;
  for (const fs::path& part : p.lexically_normal()) {
    if (leading && part == "..") continue;
    leading = false;
    stripped /= part;
  }
  for (const std::string& root : search_roots) {
    tried.push_back((fs::path(root) / stripped).lexically_normal().string());
  }
  std::string list;
  for (const std::string& t : tried) {
    if (fs::exists(t)) return t;
    list += (list.empty() ? "" : ", ") + t;
  }
  throw std::invalid_argument(where + ": cannot find '" + file + "' (tried: " + list + ")");
}

ScenarioSpec ParseScenarioSpec(const std::string& path,
                               const std::vector<std::string>& search_roots) {
  const nlohmann::json doc = base::ParseJsonFile(path, "scenario");
  const base::JsonNode root(doc, path);
  root.CheckKeys({"name", "description", "robot", "srdf", "package_paths", "objects",
                  "robot_chains", "collision", "writhe_report", "start", "problem", "tasks",
                  "final_pose", "success", "aico", "rrt", "check_resolution", "frozen_joints"});
  const std::string dir = fs::path(path).parent_path().string();
  ScenarioSpec s;
  s.source = path;
  s.name = root.String("name", fs::path(path).stem().string());
  root.String("description", "");
  {
    const base::JsonNode rn = root.At("robot");
    s.robot = ResolveDataFile(rn.String(), dir, search_roots, rn.Where());
  }
  if (root.Has("srdf")) {
    const base::JsonNode sn = root.At("srdf");
    s.srdf = ResolveDataFile(sn.String(), dir, search_roots, sn.Where());
  }
  if (root.Has("package_paths")) {
    for (const std::string& p : root.At("package_paths").Strings()) {
      s.package_paths.push_back(fs::path(p).is_absolute() ? p : (fs::path(dir) / p).string());
    }
  }
  if (root.Has("objects")) {
    const base::JsonNode objs = root.At("objects");
    NameList earlier;
    for (size_t i = 0; i < objs.Size(); ++i) {
      s.objects.push_back(ReadObject(objs.At(i), dir, search_roots, earlier));
      earlier.push_back(s.objects.back().name);
    }
  }
  if (root.Has("frozen_joints")) {
    const base::JsonNode fj = root.At("frozen_joints");
    s.frozen_where = fj.Where();
    for (size_t i = 0; i < fj.Size(); ++i) s.frozen_joints.push_back(fj.At(i).String());
  }
  if (root.Has("robot_chains")) {
    const base::JsonNode rc = root.At("robot_chains");
    for (size_t i = 0; i < rc.Size(); ++i) s.robot_chains.push_back(ReadChainDescription(rc.At(i)));
  }
  if (root.Has("collision")) s.collision = ReadCollision(root.At("collision"));
  if (root.Has("writhe_report")) {
    const base::JsonNode wn = root.At("writhe_report");
    wn.CheckKeys({"chain", "object", "object_chain"});
    s.writhe_report =
        WritheReportSpec{Name(wn, "chain"), Name(wn, "object"), Name(wn, "object_chain")};
  }
  s.start = ReadStart(root.At("start"));
  if (s.start.kind == StartKind::kCoil && !s.writhe_report) {
    root.At("start").At("coil").Fail("a coil start needs \"writhe_report\"");
  }
  if (root.Has("problem")) s.problem = ReadProblem(root.At("problem"));
  const base::JsonNode tasks = root.At("tasks");
  NameList object_names;
  for (const ObjectSpec& o : s.objects) object_names.push_back(o.name);
  for (size_t i = 0; i < tasks.Size(); ++i) {
    s.tasks.push_back(ReadTask(tasks.At(i), object_names));
  }
  if (root.Has("final_pose")) {
    s.final_pose = ReadFinalPose(root.At("final_pose"));
    if (s.final_pose.init == FinalPoseInit::kUnwrapped && s.start.kind != StartKind::kCoil) {
      root.At("final_pose").At("init").Fail("\"unwrapped\" needs a coil start");
    }
  }
  if (root.Has("success")) s.success = ReadSuccess(root.At("success"));
  s.aico_attempts.resize(1);
  s.aico_attempts[0].max_iterations = s.aico.max_iterations;
  if (root.Has("aico")) ReadAico(root.At("aico"), &s);
  if (root.Has("rrt")) s.rrt = ReadRrt(root.At("rrt"), &s);
  s.check_resolution = root.Number(
      "check_resolution", s.rrt.resolution > 0 ? s.rrt.resolution : 0.02, kMinResolution, 10.0);
  return s;
}

}  // namespace planning
