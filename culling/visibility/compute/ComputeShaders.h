#pragma once
// The GLSL 4.50 compute shaders of the gl-compute backend, one per stage of a fetch's chain:
//  setup     one workgroup a chunk of 64 pieces: every piece's vertices carried to the screen in
//            double, the faces that cannot decide it dropped, its pixel box, key bounds, edge
//            functions and depth plane (the cpu backend's CpuTriangleSetup, operation for
//            operation), and the chunk's rectangle;
//  binCount  one invocation a chunk: the screen tiles its rectangle reaches counted;
//  binScan   one workgroup: the counts made offsets (and the lists' capacity checked);
//  binFill   one invocation a chunk: listed in each of its tiles (in any order);
//  binSort   one workgroup a tile: its list sorted, so that it is in issue order;
//  evaluate  one workgroup a tile, an invocation a pixel: the tile's chunks walked in issue order,
//            each pixel keeping its stored depth (and an order-independent pass' planes) in
//            registers, tests clearing their answers with atomics.
// Every float and double operation whose rounding the answers depend on is `precise` (no fused
// multiply-add the source does not write) or an explicit fma() where the cpu backend's SIMD loops
// fuse one (mulAdd).
#include <string>

namespace cdb::compute {

// `nativeFma`: GLSL's fma() rounds once on this driver (it need not: NVIDIA's does, llvmpipe's
// rounds twice); otherwise the shaders compute a * b + c rounded once in double arithmetic.
[[nodiscard]] std::string setupShader(bool nativeFma);
[[nodiscard]] std::string binCountShader(bool nativeFma);
[[nodiscard]] std::string binScanShader(bool nativeFma);
[[nodiscard]] std::string binFillShader(bool nativeFma);
[[nodiscard]] std::string binSortShader(bool nativeFma);
[[nodiscard]] std::string evaluateShader(bool nativeFma);
// A shader answering the shaders' mulAdd for each vec4 (a, b, c, _) of the buffer at binding 0,
// into its w: how the backend finds out whether the driver's fma() rounds once.
[[nodiscard]] std::string fmaProbeShader(bool nativeFma);

}  // namespace cdb::compute
