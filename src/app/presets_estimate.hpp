#pragma once
// What accuracy costs on this scene (`voigt check SCENE --presets`): the scene as written
// and the scene under each preset (fast, balanced, accurate; scene/presets.hpp), each with
// the value of every preset knob, where it came from, and the estimated steps and wall
// time from its own calibration (app/estimate.hpp). The measured error of the presets is
// in perf/accuracy/README.md; on this scene it is not measured, and the text says so.
#include <mpi.h>

#include <string>

#include "app/estimate.hpp"
#include "scene/load.hpp"
#include "scene/scene.hpp"

namespace voigt {

// Collective (one calibration per variant, one after another). `scene` was loaded from
// `path` with `opts`; a preset variant loads it again with `--set preset=NAME` appended,
// which replaces the scene's own preset (keys written in the scene or --set still win).
// sceneEstimate: the scene's estimate when already made (voigt check --estimate), or null.
// Returns the text to print (the same on every rank).
std::string presetsReport(const Scene& scene, const std::string& path, const LoadOptions& opts, MPI_Comm comm,
                          const Estimate* sceneEstimate = nullptr);

} // namespace voigt
