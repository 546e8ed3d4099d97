#pragma once
// Samples only where the image has an edge (RenderSettings::adaptive_threshold,
// docs/physics.md), for the deterministic methods: the centre sample of every
// pixel of the rendered rows and of the rows next to them (so that a pixel's
// value does not depend on which rows a process renders), then per pixel
// either that centre or, where it differs from a neighbour's, the pixel's
// samples_per_pixel stratified samples, drawn from the pixel's own random
// stream as without the threshold, so that such a pixel is the same to the
// bit. Ray by ray (the CPU's integrators) or through a batched integrator
// (the GPU's), as render/renderer.cpp renders without the threshold.
#include "obscura/render/renderer.h"
#include "obscura/render/sensor_render.h"

namespace obscura::render_detail {

void render_adaptive_rays(const SensorRender& job, const RenderOptions& options, SensorImage& image,
                          RowCounters& counters);

void render_adaptive_batches(const SensorRender& job, const BatchIntegrator& integrator,
                             const RenderOptions& options, SensorImage& image,
                             RowCounters& counters);

}  // namespace obscura::render_detail
