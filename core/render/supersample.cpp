// The image loop of supersample.h on TBB: one task per row, simple partitioner.
#include "core/render/supersample.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <mutex>

namespace glintlab {

Image render_image(int width, int height, std::vector<std::string> channels, int threads,
                   const PixelFunction& pixel, const RowProgress& progress) {
  Image img(width, height, std::move(channels));
  std::mutex mutex;
  long done = 0;
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(
        tbb::blocked_range<int>(0, height, 1),
        [&](const tbb::blocked_range<int>& rows) {
          for (int y = rows.begin(); y != rows.end(); ++y) {
            for (int x = 0; x < width; ++x) pixel(x, y, &img.at(x, y, 0));
            if (progress) {
              const std::lock_guard<std::mutex> lock(mutex);
              progress(++done, height);
            }
          }
        },
        tbb::simple_partitioner());
  });
  return img;
}

}  // namespace glintlab
