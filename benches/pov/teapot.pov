// POV-Ray 3.7 equivalent of scenes/teapot.scene, for benches/vs-povray.sh.
// Right-handed, z up: `right -x` flips POV-Ray's left-handed default. The 32 patches come from
// scenes/teapot.bpt, converted by vs-povray.sh into teapot-patches.inc (one bicubic_patch
// each). POV-Ray tessellates bicubic patches into triangles (type 1, flatness 0.01, 2^3 steps
// per side); `render` intersects the exact surface.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera {
  location <5.5, -8, 6>
  sky <0, 0, 1>
  up <0, 0, 1>
  right <-1, 0, 0>
  angle 34
  look_at <0.45, 0, 1.35>
}
background { rgb <0.25, 0.3, 0.4> }
light_source { <8, -6, 14> rgb 1 }
plane {
  z, 0
  pigment { rgb <0.55, 0.5, 0.45> }
  finish { ambient 0.2 diffuse 0.8 }
}
union {
  #include "teapot-patches.inc"
  pigment { rgb <0.85, 0.85, 0.8> }
  finish { ambient 0.15 diffuse 0.7 phong 0.5 phong_size 40 }
}
