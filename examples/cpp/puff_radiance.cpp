// A warm Gaussian smoke puff in front of a hot plate, seen in the LWIR
// (emission–absorption): builds the scene in code, renders it and prints the
// image's mean band radiance and the apparent temperature range.
#include <obscura/obscura.h>

#include <algorithm>
#include <cstdio>
#include <numeric>

int main() {
  using namespace obscura;
  try {
    GaussianPuffSpec puff;
    puff.center_m = {0, -10, 2};
    puff.radius_m = 1.5;
    puff.resolution = 48;
    puff.wavelengths_um = {8.0, 12.0};
    puff.peak_sigma_a = {0.6, 0.5};
    puff.peak_sigma_s = {0.1, 0.05};
    puff.g = {0.5, 0.4};
    puff.ambient_temperature_k = 288.0;
    puff.temperature_excess_k = 15.0;

    Scene scene;
    scene.static_clouds.push_back(
        std::make_shared<GridMedium>(std::make_shared<VoxelGrid>(make_gaussian_puff(puff))));
    scene.surfaces.push_back(std::make_unique<BoxSurface>("plate", SurfaceMaterial{330.0, 0.9},
                                                          BBox3({-3, 0, 0}, {3, 1, 4})));
    scene.sky = Sky::blackbody(250.0, true);
    Sensor camera;
    camera.name = "lwir";
    camera.camera = PinholeCamera({0, -30, 2}, {0, 0, 2}, {0, 0, 1}, 20.0, 64, 48);
    camera.bands = {Band::preset("lwir")};
    scene.sensors.push_back(camera);
    stage_scene(scene, 0.0);

    const SensorImage image = render_sensor(scene, scene.sensors[0]);
    const BandImage& lwir = image.bands[0];
    const double mean = std::accumulate(lwir.radiance.begin(), lwir.radiance.end(), 0.0) /
                        static_cast<double>(lwir.radiance.size());
    const auto [lo, hi] =
        std::minmax_element(lwir.apparent_temperature.begin(), lwir.apparent_temperature.end());
    std::printf(
        "obscura %s: %dx%d px, mean LWIR radiance %.4f W m-2 sr-1, apparent temperature %.2f-%.2f "
        "K\n",
        kVersion, image.width, image.height, mean, *lo, *hi);
    return 0;
  } catch (const Error& e) {
    std::fprintf(stderr, "puff_radiance: %s\n", e.what());
    return 1;
  }
}
