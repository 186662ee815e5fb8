#version 460
// Raster fill-rate calibration: writes the layer and the fragment's depth bits (what a
// visibility buffer writes: two words per pixel). See calibrate_raster.vert.
layout(location = 0) flat in uint in_layer;
layout(location = 0) out uvec2 out_id;

void main() { out_id = uvec2(in_layer, floatBitsToUint(gl_FragCoord.z)); }
