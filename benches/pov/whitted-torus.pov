// POV-Ray 3.7 equivalent of scenes/whitted-torus.scene, for benches/vs-povray.sh: the torus of
// torus.pov in glass (transmit 0.7, ior 1.5) over a reflective checkerboard floor z = -1.5,
// recursion depth 5. The finishes approximate Stam's illumination model; the geometry, lights,
// camera and ray tree depth match. Right-handed, z up: `right -x` flips POV-Ray's default.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 5 }
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
  pigment { rgbt <0.8, 0.3, 0.2, 0.7> }
  finish { ambient 0.1 diffuse 0.7 phong 0.5 phong_size 40 reflection 0.1 }
  interior { ior 1.5 }
}
plane {
  z, -1.5
  pigment { checker rgb 0.9, rgb 0.15 scale 1 }
  finish { ambient 0.1 diffuse 0.6 reflection 0.3 phong 0.3 phong_size 20 }
}
