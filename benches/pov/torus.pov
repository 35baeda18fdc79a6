// POV-Ray 3.7 equivalent of scenes/torus.scene, for benches/vs-povray.sh.
// Right-handed, z up: `right -x` flips POV-Ray's left-handed default.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera {
  location <0, -8, 5>
  sky <0, 0, 1>
  up <0, 0, 1>
  right <-1, 0, 0>
  angle 50
  look_at <0, 0, 0>
}
background { rgb 0.2 }
light_source { <5, -5, 10> rgb 1 }
torus {
  2, 1
  rotate x*90
  pigment { rgb <0.8, 0.3, 0.2> }
  finish { ambient 0.1 diffuse 0.7 phong 0.5 phong_size 40 }
}
