// `voigt check SCENE --presets`: see presets_estimate.hpp.
#include "app/presets_estimate.hpp"

#include <algorithm>
#include <iomanip>
#include <sstream>
#include <vector>

#include "scene/presets.hpp"

namespace voigt {

namespace {
std::string num(double v) {
  std::ostringstream os;
  os << v; // 0.9, 1e-06: as the preset table writes them, give or take the exponent
  return os.str();
}

bool hasEffect(const Scene& s, const char* e) { return std::find(s.effects.begin(), s.effects.end(), e) != s.effects.end(); }

// The scene tree's scalar at section.key ("" if absent). A const node: lookups insert nothing.
std::string treeValue(const Scene& s, const PresetKnob& k) {
  const YAML::Node& root = s.root;
  const YAML::Node sec = root[k.section];
  if (!sec.IsDefined() || !sec.IsMap()) return "";
  const YAML::Node v = sec[k.key];
  return v.IsDefined() && v.IsScalar() ? v.Scalar() : "";
}

// The value the run will use: the core knobs as the loader resolved them; the effect-owned
// ones (reinit) from the tree, else the effect's default (src/effects/reinit.cpp reads them).
std::string knobValue(const Scene& s, const PresetKnob& k) {
  const std::string path = std::string(k.section) + "." + k.key;
  if (path == "time.cfl") return num(s.time.cfl);
  if (path == "advection.limiter") return s.advection.limiter;
  if (path == "projection.operator") return s.projection.op == ProjectionCfg::Op::Exact ? "exact" : "approximate";
  if (path == "projection.tolerance") return num(s.projection.tolerance);
  if (path == "projection.preconditioner") return s.projection.preconditioner;
  if (std::string(k.section) == "reinit" && !hasEffect(s, "reinit")) return "-";
  const std::string v = treeValue(s, k);
  if (!v.empty()) return v;
  if (path == "reinit.interval") return "1";
  if (path == "reinit.iterations") return "2";
  return "(default)";
}

// Where the value came from: applyPreset's note for a scene with a preset, else the tree.
std::string knobOrigin(const Scene& s, const PresetKnob& k) {
  const std::string path = std::string(k.section) + "." + k.key, section = k.section;
  std::string origin;
  if (section == "reinit" && !hasEffect(s, "reinit")) return "unused: reinit is not in the effects";
  for (const std::string& n : s.presetNotes)
    if (n.rfind(path + " = ", 0) == 0) {
      const size_t kept = n.find(" (kept from");
      origin = kept == std::string::npos ? "preset " + s.preset : n.substr(kept + 2, n.size() - kept - 3);
    }
  if (origin.empty()) origin = treeValue(s, k).empty() ? "default" : "scene or --set";
  if (origin == "default" && path == "projection.preconditioner" && s.projection.preconditionerAuto)
    origin = s.projection.op == ProjectionCfg::Op::Exact
                 ? "default with the exact operator"
                 : "default by size and phases (multigrid from 32^3 cells or two densities, else sgs)";
  if (origin == "default" && path == "projection.tolerance" && s.projection.toleranceAuto &&
      s.projection.tolerance == ProjectionCfg::kTwoPhaseExactTolerance)
    origin = "default: exact operator, two densities";
  if (path == "time.cfl" && s.time.dt > 0) origin += "; unused: fixed time.dt";
  if (section == "projection" && !hasEffect(s, "navier_stokes")) origin += "; unused: no navier_stokes";
  return origin;
}

std::string stepsText(const Estimate& e) { return std::to_string(e.steps) + (e.stepsLowerBound ? " or more" : ""); }
std::string wallText(const Estimate& e) { return durationText(e.wallSeconds) + (e.stepsLowerBound ? " or more" : ""); }

struct Variant {
  std::string label;  // scene | fast | balanced | accurate
  std::string header; // what the variant is
  Scene scene;
  Estimate est;
};

std::string block(const Variant& v) {
  std::ostringstream os;
  os.precision(3);
  os << std::left << std::setw(11) << v.label << v.header << "\n";
  for (const PresetKnob& k : presetKnobs("balanced")) { // every preset sets the same knobs
    const std::string path = std::string(k.section) + "." + k.key;
    os << "  " << std::setw(27) << path << std::setw(13) << knobValue(v.scene, k) << knobOrigin(v.scene, k) << "\n";
  }
  const Estimate& e = v.est;
  os << "  steps      " << stepsText(e) << " to t = " << e.tEnd << ", dt = " << e.dt << " ("
     << (e.fixedDt ? std::string("fixed") : e.dtReason) << ")\n";
  os << "  wall time  " << wallText(e) << " = " << e.steps << " steps x " << e.secondsPerStep << " s + "
     << durationText(e.writeSeconds) << " writing; " << e.cellStepsPerSecond << " cell-steps/s\n";
  return os.str();
}
} // namespace

std::string presetsReport(const Scene& scene, const std::string& path, const LoadOptions& opts, MPI_Comm comm,
                          const Estimate* sceneEstimate) {
  std::vector<Variant> vs;
  vs.push_back({"scene",
                scene.preset.empty() ? "as written (no preset): its own values, else Voigt's defaults"
                                     : "as written, with its preset: " + scene.preset,
                scene, sceneEstimate ? *sceneEstimate : estimateRun(scene, comm)});
  for (const std::string& p : presetNames()) {
    if (p == scene.preset) { // the same tree: reuse the scene's calibration
      vs.push_back({p, "preset: " + p + " = the scene's own preset: the same as 'scene' (its calibration reused)", scene, vs[0].est});
      continue;
    }
    LoadOptions o = opts;
    o.overrides.push_back("preset=" + p); // after the command's --set: it replaces the scene's preset
    Scene s = loadScene(path, o);
    Estimate e = estimateRun(s, comm);
    vs.push_back({p, "preset: " + p + (scene.preset.empty() ? "" : " in place of the scene's " + scene.preset) +
                         "; keys written in the scene or --set win",
                  std::move(s), e});
  }

  std::ostringstream os;
  os.precision(3);
  os << "\npresets    the scene as written and under each preset (scene key 'preset', scene/presets.hpp),\n"
     << "           each with its own calibration: 1 warm-up + " << vs[0].est.calibrationSteps
     << " steps in memory, nothing written\n";
  if (!scene.preset.empty())
    os << "           the scene has preset: " << scene.preset << " (its 'scene' variant); a variant below replaces "
       << "that preset\n           by its own, and a knob written in the scene or --set still wins over it\n";
  os << "\n";
  for (const Variant& v : vs) os << block(v) << "\n";

  os << "summary    " << std::left << std::setw(10) << "variant" << std::setw(16) << "steps" << std::setw(18)
     << "est. wall time" << "x scene\n";
  for (const Variant& v : vs) {
    const double r = vs[0].est.wallSeconds > 0 ? v.est.wallSeconds / vs[0].est.wallSeconds : 0;
    os << "           " << std::setw(10) << v.label << std::setw(16) << stepsText(v.est) << std::setw(18)
       << wallText(v.est) << std::fixed << std::setprecision(2) << r << std::defaultfloat << std::setprecision(3)
       << "\n";
  }
  std::string kept; // the same for every preset: it depends only on the keys the scene writes
  for (const PresetKnob& k : presetKnobs(vs[1].label))
    if (knobOrigin(vs[1].scene, k).rfind("kept", 0) == 0) kept += std::string(kept.empty() ? "" : ", ") + k.section + "." + k.key;
  if (!kept.empty())
    os << "kept       the scene or --set writes " << kept << ":\n           every preset keeps "
       << "these; remove them from the scene to see what a preset would do with them\n";
  os << "measured error of each preset: perf/accuracy/README.md (section \"Presets\": error and time against the\n"
     << "           base on Taylor-Green, Zalesak and elastic Couette; the 'preset' rows of each case under \"Results\")\n";
  os << "assumes    the presets were chosen on Taylor-Green, Zalesak and elastic Couette: their error on this\n"
     << "           scene is not measured (run it under two presets and compare what matters to you);\n"
     << "           each wall time is its variant's own short calibration on this machine as loaded now, so\n"
     << "           variants with the same settings differ by timing noise; steps and wall times carry the\n"
     << "           assumptions of 'voigt check --estimate' (the rate holds; 'or more': dt may shrink)\n";
  return os.str();
}

} // namespace voigt
