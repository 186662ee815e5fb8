// Include first in a CPU mirror of GLSL arithmetic marked `precise` (bvh.cpp, material_eval.cpp,
// texture.cpp): no fused multiply-add contraction in the rest of the file, whatever -march the
// project is built with, so the mirror rounds exactly like the shader.
#pragma once
#if defined(__clang__)
#pragma clang fp contract(off)
#elif defined(__GNUC__)
#pragma GCC optimize("fp-contract=off")
#endif
