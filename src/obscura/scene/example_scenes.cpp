#include "obscura/scene/example_scenes.h"

#include "obscura/medium/gaussian_puff.h"
#include "obscura/medium/grid_medium.h"

namespace obscura {

Scene make_study_scene(StudyScene which, int width, int height, RenderMethod method,
                       int resolution) {
  const bool visible = which == StudyScene::kVisible;
  GaussianPuffSpec spec;
  spec.center_m = {-2, -12, 3};
  spec.radius_m = 2.5;
  spec.extent_radii = 3.5;
  spec.resolution = resolution;
  spec.wavelengths_um = {visible ? 0.55 : 10.0};
  spec.peak_sigma_a = {visible ? 0.05 : 0.30};
  spec.peak_sigma_s = {visible ? 0.45 : 0.05};
  spec.g = {visible ? 0.6 : 0.4};
  spec.ambient_temperature_k = 288;
  spec.temperature_excess_k = 12;
  Scene scene;
  scene.medium =
      std::make_shared<GridMedium>(std::make_shared<VoxelGrid>(make_gaussian_puff(spec)));
  scene.surfaces.push_back(
      std::make_unique<GroundPlane>("ground", SurfaceMaterial{288, visible ? 0.8 : 0.95}, 0.0));
  scene.surfaces.push_back(std::make_unique<BoxSurface>("target", SurfaceMaterial{330, 0.9},
                                                        BBox3({-3, 0, 0}, {3, 6, 2.5})));
  if (visible) {
    scene.sky = Sky::zenith_table({0, 90}, {0.55}, {{60.0}, {60.0}});
    scene.sun.enabled = true;
    scene.sun.azimuth_deg = 200;
    scene.sun.elevation_deg = 40;
  } else {
    scene.sky = Sky::blackbody(250, true);
  }
  Sensor sensor;
  sensor.name = "cam";
  // Framing the puff and the target behind it.
  sensor.camera = PinholeCamera({0, -40, 4}, {-1, -6, 2.5}, {0, 0, 1}, 20.0, width, height);
  sensor.bands = {visible ? Band::flat("green", 0.545, 0.555) : Band::flat("10um", 9.95, 10.05)};
  scene.sensors.push_back(sensor);
  scene.settings.method = method;
  scene.settings.spectral_nodes_per_band = 1;
  return scene;
}

}  // namespace obscura
