#include "fastcorot/core/parallel.h"

namespace fastcorot::detail {

void run_tasks(int threads, int count, void (*call)(const void*, int), const void* context) {
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int i = 0; i < count; ++i) call(context, i);
}

}  // namespace fastcorot::detail
