// POV-Ray 3.7 equivalent of scenes/barth.scene, for benches/vs-povray.sh.
// Barth's sextic 4(phi^2 x^2 - y^2)(phi^2 y^2 - z^2)(phi^2 z^2 - x^2) - (1 + 2 phi)(x^2 + y^2 + z^2 - 1)^2,
// expanded to the same f64 coefficients `render` traces (toolkit_benches::rays::barth_sextic),
// clipped to the box [-2, 2]^3. `sturm` asks for POV-Ray's Sturm-sequence solver (its default for
// order > 4 as well). Right-handed, z up: `right -x` flips POV-Ray's left-handed default.
#version 3.7;
global_settings { assumed_gamma 1.0 }
camera {
  location <5, -9, 6>
  sky <0, 0, 1>
  up <0, 0, 1>
  right <-1, 0, 0>
  angle 30
  look_at <0, 0, 0>
}
background { rgb <0.05, 0.05, 0.1> }
light_source { <10, -10, 20> rgb 0.8 }
light_source { <-10, -5, 5> rgb <0.3, 0.3, 0.4> }
polynomial {
  6,
    xyz(0, 0, 0): -4.23606797749978981e0,
    xyz(0, 0, 2): 8.47213595499957961e0,
    xyz(0, 0, 4): -4.23606797749978981e0,
    xyz(0, 2, 0): 8.47213595499957961e0,
    xyz(0, 2, 2): -8.47213595499957961e0,
    xyz(0, 2, 4): 1.04721359549995796e1,
    xyz(0, 4, 0): -4.23606797749978981e0,
    xyz(0, 4, 2): -2.74164078649987388e1,
    xyz(2, 0, 0): 8.47213595499957961e0,
    xyz(2, 0, 2): -8.47213595499957961e0,
    xyz(2, 0, 4): -2.74164078649987388e1,
    xyz(2, 2, 0): -8.47213595499957961e0,
    xyz(2, 2, 2): 6.77770876399966369e1,
    xyz(2, 4, 0): 1.04721359549995796e1,
    xyz(4, 0, 0): -4.23606797749978981e0,
    xyz(4, 0, 2): 1.04721359549995796e1,
    xyz(4, 2, 0): -2.74164078649987388e1
  sturm
  clipped_by { box { <-2, -2, -2>, <2, 2, 2> } }
  bounded_by { box { <-2, -2, -2>, <2, 2, 2> } }
  pigment { rgb <0.9, 0.75, 0.3> }
  finish { ambient 0.15 diffuse 0.7 phong 0.4 phong_size 30 }
}
