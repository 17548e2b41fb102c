#pragma once
// Point and line probes: trilinear samples of output fields appended to
// DIR/probe_<name>.csv by rank 0.
#include "io/fields_out.hpp"
#include "kernels/probes.hpp"
#include "scene/scene.hpp"

#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace voigt {

class ProbeSet {
 public:
  // resumeAt >= 0: a restarted run at that time appends to the existing CSVs
  // (no new header) and takes the next interval sample after it.
  ProbeSet(const Grid& g, const std::vector<Probe>& probes, std::string dir, double resumeAt = -1);
  // Collective over g.comm. Ghost layers must be exchanged first. Honours each
  // probe's interval (0 = every call); force samples regardless.
  void sample(double t, const std::vector<OutField>& available, bool force = false);
  // Would sample(t) sample anything? Lets the caller skip gathering the fields.
  bool due(double t) const;

 private:
  // Per-axis stencil of one point: base local index and weight of index+1,
  // for node and cell interpolation. Kept on the device for the kernels.
  using IdxView = ProbeIdx;     // kernels/probes.hpp
  using WView = ProbeWeights;
  struct State {
    Probe probe;
    std::vector<Vec3> pts;   // all points of the probe (global)
    std::vector<int> local;  // positions in pts this rank samples
    IdxView idx;             // [owned point][node xyz, cell xyz, cell step xyz]
    WView w;
    std::unique_ptr<std::ofstream> out; // rank 0 only
    bool headerDone = false;
    bool sampled = false;
    double next = 0;          // earliest time of the next interval sample
    double lastT = 0;         // time of the last row (valid when sampled)
  };
  void writeRows(State& s, double t, const std::vector<const OutField*>& fs,
                 const std::vector<double>& vals);

  Grid g_;
  std::string dir_;
  std::vector<State> probes_;
};

} // namespace voigt
