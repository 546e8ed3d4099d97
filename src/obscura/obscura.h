#pragma once
// obscura's public API in one include (find_package(obscura), target
// obscura::obscura; docs/architecture.md has the layers and what each holds).
// A typical program loads a scene (scene/scene.h), renders it at one time
// (render/renderer.h) or over a sequence (sequence/sequence_runner.h), and
// measures or writes what it got (analysis/, report/). Every error is an
// obscura::Error (InputError for bad input, naming the file and field).
#include "obscura/analysis/region_stats.h"
#include "obscura/analysis/screening_metrics.h"
#include "obscura/analysis/target_mask.h"
#include "obscura/core/band.h"
#include "obscura/core/error.h"
#include "obscura/core/planck.h"
#include "obscura/core/tabulated_spectrum.h"
#include "obscura/core/version.h"
#include "obscura/film/sensor_image.h"
#include "obscura/gpu/frame_integrator.h"
#include "obscura/gpu/gpu_device.h"
#include "obscura/io/cloud_manifest.h"
#include "obscura/io/provenance.h"
#include "obscura/io/vdb_keyframe.h"
#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/grid_medium.h"
#include "obscura/medium/homogeneous_medium.h"
#include "obscura/medium/voxel_grid.h"
#include "obscura/optics/material.h"
#include "obscura/optics/mie.h"
#include "obscura/optics/size_distribution.h"
#include "obscura/prep/prepare.h"
#include "obscura/render/integrator_registry.h"
#include "obscura/render/renderer.h"
#include "obscura/report/render_output.h"
#include "obscura/report/sequence_output.h"
#include "obscura/scene/render_settings.h"
#include "obscura/scene/scene.h"
#include "obscura/sequence/sequence_runner.h"
#include "obscura/validation/validation_cases.h"
