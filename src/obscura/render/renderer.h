#pragma once
// Renders sensors' images of a staged scene (film/sensor_image.h): the pixel
// and sample loop around an integrator (render/integrator.h). Per pixel it
// draws stratified sample positions, makes the camera ray, finds its first
// surface once, asks the integrator for each band's spectral radiance and
// transmittance at the band's nodes, weights them by the band's quadrature,
// applies the atmosphere between the sensor and the scene (scene/atmosphere.h)
// and inverts the band radiance to an apparent temperature. Monte Carlo
// methods get standard errors and, with a target relative standard error,
// further rounds of samples per pixel.
//
// Deterministic methods may refine only where the image has an edge
// (RenderSettings::adaptive_threshold): every pixel's centre first, then the
// full stratified samples in the pixels whose centre differs from a
// neighbour's; the other pixels keep their centre, which for an image smooth
// across a pixel differs from the pixel's mean by its curvature only. The
// image's samples_per_pixel says which pixels took which.
//
// An integrator that marches whole images (render/batch_integrator.h: the
// GPU's) gets every camera ray of a batch of rows at once, after the CPU has
// found their first surfaces; the renderer then adds the background and the
// band sums per ray as above, so the same samples give the same pixels.
//
// Determinism: pixel (x, y) of a sensor draws from its own stream, selected
// by its index y·width + x under settings.seed (core/rng.h); rows go to TBB
// threads but share no state, so images are bit-identical for any thread
// count.
#include <functional>
#include <memory>

#include "obscura/film/sensor_image.h"
#include "obscura/render/integrator.h"
#include "obscura/render/integrator_registry.h"
#include "obscura/scene/scene.h"

namespace obscura {

struct RenderOptions {
  // Called as rows complete, with (rows done, rows total); may be called from any thread.
  // With an adaptive threshold every row counts twice, once for its centres
  // and once for its samples (render/adaptive_samples.h).
  std::function<void(int, int)> progress;
  // Render only rows y with y mod row_stride == row_offset (a process's share
  // of the image, sequence/distributed_frame.h); the other rows stay zero.
  // A pixel's value does not depend on which rows are rendered.
  int row_offset = 0, row_stride = 1;
};

// The rows of an image of `height` rows that `options` renders.
int rendered_row_count(int height, const RenderOptions& options);

// The image `sensor` renders into, zero everywhere: its bands, and a standard
// error image when the method is Monte Carlo.
SensorImage blank_sensor_image(const Sensor& sensor, bool monte_carlo);

// Sensor `sensor` of the scene through an integrator made for `spectra`
// (`spectra[sensor]` its bands' nodes). Threads and seed: scene.settings.
SensorImage render_sensor(const Scene& scene, int sensor, const Integrator& integrator,
                          const FrameSpectra& spectra, const RenderOptions& options = {});

// One sensor on its own: prepares the method for that sensor only, with the
// CPU's integrators (render/integrator_registry.h; "device": "gpu" takes
// gpu/frame_integrator.h and the overload above).
SensorImage render_sensor(const Scene& scene, const Sensor& sensor,
                          const RenderOptions& options = {});

}  // namespace obscura
