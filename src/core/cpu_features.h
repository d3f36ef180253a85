// What the processor offers beyond the baseline the project is compiled for (x86-64), for the
// few loops that have a variant compiled for more (src/fit/row_kernels.h, luminance in
// core/image.h). Each such variant gives the same bits as the baseline one: only the speed
// depends on the answer.
#pragma once

namespace surrogate {

// AVX2, checked once; false on other architectures.
bool cpuHasAvx2();

}  // namespace surrogate
