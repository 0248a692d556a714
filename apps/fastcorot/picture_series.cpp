#include "picture_series.h"

#include "run_command.h"

#include "fastcorot/core/error.h"
#include "fastcorot/render/offscreen_renderer.h"

#include <filesystem>

namespace fastcorot::cli {

struct PictureSeries::Impl {
  std::filesystem::path dir;
  int digits = 5;
  DrawOptions draw;
  Camera camera;
  SceneDrawer drawer;
  OffscreenRenderer renderer;

  Impl(const std::string& folder, const PictureOptions& options,
       const Simulation<double>& simulation, long last_step, const ImageSize& size)
      : dir(folder), draw(draw_options(options)), renderer(size.width, size.height) {
    digits = std::max(5, static_cast<int>(std::to_string(last_step).size()));
    const DrawGeometry geometry = drawer.draw(simulation, draw);
    camera = frame_camera(geometry.framing_bounds(), simulation.gravity,
                          static_cast<double>(size.width) / size.height, camera_options(options));
  }
};

PictureSeries::PictureSeries(const std::string& dir, const PictureOptions& options,
                             const Simulation<double>& simulation, long last_step) {
  const ImageSize size = parse_image_size(options.size);
  draw_options(options);  // reports bad options before any folder is made
  camera_options(options);
  make_output_folder(dir, "--png");
  impl_ = std::make_unique<Impl>(dir, options, simulation, last_step, size);
}

PictureSeries::~PictureSeries() = default;

void PictureSeries::write(const Simulation<double>& simulation) {
  std::string number = std::to_string(simulation.steps_done());
  if (static_cast<int>(number.size()) < impl_->digits)
    number.insert(0, static_cast<std::size_t>(impl_->digits) - number.size(), '0');
  const Image image =
      impl_->renderer.render(impl_->drawer.draw(simulation, impl_->draw), impl_->camera);
  write_png(impl_->dir / ("step_" + number + ".png"), image);
}

}  // namespace fastcorot::cli
