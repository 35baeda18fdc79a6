// POV-Ray 3 scene file, written by benches/spd/generate.py
background { color red 0.078 green 0.361 blue 0.753 }

camera {
    location <-1, -2.61313, 0.5>
    direction <0, 1, 0>
    right     <0.828427, -0, -0>
    up        <0, -0, 0.828427>
} // camera

light_source {
    <3, -2.61313, 3> color red 0.57735 green 0.57735 blue 0.57735
} // light

light_source {
    <-4, -2.61313, 1> color red 0.57735 green 0.57735 blue 0.57735
} // light

light_source {
    <2, -2.61313, -4> color red 0.57735 green 0.57735 blue 0.57735
} // light

#declare txt001 = texture {
    pigment {
        color red 1 green 1 blue 1
    } // pigment
    finish {
        ambient 0
        diffuse 1
    } // finish
} // texture txt001

polygon {
    4,
        <2.27965, 5.22625, 3.77965>,
        <-4.27965, 5.22625, 3.77965>,
        <-4.27965, 5.22625, -2.77965>,
        <2.27965, 5.22625, -2.77965>
    texture { txt001 }
}

#declare txt002 = texture {
    pigment {
        color red 1 green 0 blue 0
    } // pigment
    finish {
        ambient 0
        diffuse 0.5
        phong 0.3  phong_size 37
        reflection 0.2
    } // finish
} // texture txt002

cone {
    <0.287693, 1.7277, 0>, 0.07412,
    <0.930995, 2.61313, 0>, 0.07412 open
    texture { txt002 }
}

sphere { <0.930995, 2.61313, 0>, 0.07412  texture { txt002 } }

cone {
    <0.930995, 2.61313, 0>, 0.07412,
    <0.287693, 3.49855, 0>, 0.07412 open
    texture { txt002 }
}

sphere { <0.287693, 3.49855, 0>, 0.07412  texture { txt002 } }

cone {
    <0.287693, 3.49855, 0>, 0.07412,
    <-0.753191, 3.16035, 0>, 0.07412 open
    texture { txt002 }
}

sphere { <-0.753191, 3.16035, 0>, 0.07412  texture { txt002 } }

cone {
    <-0.753191, 3.16035, 0>, 0.07412,
    <-0.753191, 2.0659, 0>, 0.07412 open
    texture { txt002 }
}

sphere { <-0.753191, 2.0659, 0>, 0.07412  texture { txt002 } }

cone {
    <-0.753191, 2.0659, 0>, 0.07412,
    <0.287693, 1.7277, 0>, 0.07412 open
    texture { txt002 }
}

sphere { <0.287693, 1.7277, 0>, 0.07412  texture { txt002 } }

#declare txt003 = texture {
    pigment {
        color red 0 green 1 blue 0
    } // pigment
    finish {
        ambient 0
        diffuse 0.5
        phong 0.3  phong_size 37
        reflection 0.2
    } // finish
} // texture txt003

cone {
    <0.465497, 2.46188, -0.791951>, 0.07412,
    <0.753191, 3.16035, 0>, 0.07412 open
    texture { txt003 }
}

sphere { <0.753191, 3.16035, 0>, 0.07412  texture { txt003 } }

cone {
    <0.753191, 3.16035, 0>, 0.07412,
    <-1.94289e-16, 3.10258, 0.791951>, 0.07412 open
    texture { txt003 }
}

sphere { <-1.94289e-16, 3.10258, 0.791951>, 0.07412  texture { txt003 } }

cone {
    <-1.94289e-16, 3.10258, 0.791951>, 0.07412,
    <-0.753191, 2.3684, 0.489453>, 0.07412 open
    texture { txt003 }
}

sphere { <-0.753191, 2.3684, 0.489453>, 0.07412  texture { txt003 } }

cone {
    <-0.753191, 2.3684, 0.489453>, 0.07412,
    <-0.465497, 1.97242, -0.489453>, 0.07412 open
    texture { txt003 }
}

sphere { <-0.465497, 1.97242, -0.489453>, 0.07412  texture { txt003 } }

cone {
    <-0.465497, 1.97242, -0.489453>, 0.07412,
    <0.465497, 2.46188, -0.791951>, 0.07412 open
    texture { txt003 }
}

sphere { <0.465497, 2.46188, -0.791951>, 0.07412  texture { txt003 } }

#declare txt004 = texture {
    pigment {
        color red 0 green 0 blue 1
    } // pigment
    finish {
        ambient 0
        diffuse 0.5
        phong 0.3  phong_size 37
        reflection 0.2
    } // finish
} // texture txt004

cone {
    <0.287693, 3.0091, -0.791951>, 0.07412,
    <-0.287693, 3.49855, 0>, 0.07412 open
    texture { txt004 }
}

sphere { <-0.287693, 3.49855, 0>, 0.07412  texture { txt004 } }

cone {
    <-0.287693, 3.49855, 0>, 0.07412,
    <-0.465497, 2.76438, 0.791951>, 0.07412 open
    texture { txt004 }
}

sphere { <-0.465497, 2.76438, 0.791951>, 0.07412  texture { txt004 } }

cone {
    <-0.465497, 2.76438, 0.791951>, 0.07412,
    <-3.88578e-16, 1.82117, 0.489453>, 0.07412 open
    texture { txt004 }
}

sphere { <-3.88578e-16, 1.82117, 0.489453>, 0.07412  texture { txt004 } }

cone {
    <-3.88578e-16, 1.82117, 0.489453>, 0.07412,
    <0.465497, 1.97242, -0.489453>, 0.07412 open
    texture { txt004 }
}

sphere { <0.465497, 1.97242, -0.489453>, 0.07412  texture { txt004 } }

cone {
    <0.465497, 1.97242, -0.489453>, 0.07412,
    <0.287693, 3.0091, -0.791951>, 0.07412 open
    texture { txt004 }
}

sphere { <0.287693, 3.0091, -0.791951>, 0.07412  texture { txt004 } }

#declare txt005 = texture {
    pigment {
        color red 0 green 1 blue 1
    } // pigment
    finish {
        ambient 0
        diffuse 0.5
        phong 0.3  phong_size 37
        reflection 0.2
    } // finish
} // texture txt005

cone {
    <-0.287693, 3.0091, -0.791951>, 0.07412,
    <-0.930995, 2.61313, 0>, 0.07412 open
    texture { txt005 }
}

sphere { <-0.930995, 2.61313, 0>, 0.07412  texture { txt005 } }

cone {
    <-0.930995, 2.61313, 0>, 0.07412,
    <-0.287693, 2.21715, 0.791951>, 0.07412 open
    texture { txt005 }
}

sphere { <-0.287693, 2.21715, 0.791951>, 0.07412  texture { txt005 } }

cone {
    <-0.287693, 2.21715, 0.791951>, 0.07412,
    <0.753191, 2.3684, 0.489453>, 0.07412 open
    texture { txt005 }
}

sphere { <0.753191, 2.3684, 0.489453>, 0.07412  texture { txt005 } }

cone {
    <0.753191, 2.3684, 0.489453>, 0.07412,
    <0.753191, 2.85785, -0.489453>, 0.07412 open
    texture { txt005 }
}

sphere { <0.753191, 2.85785, -0.489453>, 0.07412  texture { txt005 } }

cone {
    <0.753191, 2.85785, -0.489453>, 0.07412,
    <-0.287693, 3.0091, -0.791951>, 0.07412 open
    texture { txt005 }
}

sphere { <-0.287693, 3.0091, -0.791951>, 0.07412  texture { txt005 } }

#declare txt006 = texture {
    pigment {
        color red 1 green 0 blue 1
    } // pigment
    finish {
        ambient 0
        diffuse 0.5
        phong 0.3  phong_size 37
        reflection 0.2
    } // finish
} // texture txt006

cone {
    <-0.465497, 2.46188, -0.791951>, 0.07412,
    <-0.287693, 1.7277, 0>, 0.07412 open
    texture { txt006 }
}

sphere { <-0.287693, 1.7277, 0>, 0.07412  texture { txt006 } }

cone {
    <-0.287693, 1.7277, 0>, 0.07412,
    <0.287693, 2.21715, 0.791951>, 0.07412 open
    texture { txt006 }
}

sphere { <0.287693, 2.21715, 0.791951>, 0.07412  texture { txt006 } }

cone {
    <0.287693, 2.21715, 0.791951>, 0.07412,
    <0.465497, 3.25383, 0.489453>, 0.07412 open
    texture { txt006 }
}

sphere { <0.465497, 3.25383, 0.489453>, 0.07412  texture { txt006 } }

cone {
    <0.465497, 3.25383, 0.489453>, 0.07412,
    <-5.55112e-17, 3.40508, -0.489453>, 0.07412 open
    texture { txt006 }
}

sphere { <-5.55112e-17, 3.40508, -0.489453>, 0.07412  texture { txt006 } }

cone {
    <-5.55112e-17, 3.40508, -0.489453>, 0.07412,
    <-0.465497, 2.46188, -0.791951>, 0.07412 open
    texture { txt006 }
}

sphere { <-0.465497, 2.46188, -0.791951>, 0.07412  texture { txt006 } }

#declare txt007 = texture {
    pigment {
        color red 1 green 1 blue 0
    } // pigment
    finish {
        ambient 0
        diffuse 0.5
        phong 0.3  phong_size 37
        reflection 0.2
    } // finish
} // texture txt007

cone {
    <-5.55112e-16, 2.12367, -0.791951>, 0.07412,
    <0.753191, 2.0659, 0>, 0.07412 open
    texture { txt007 }
}

sphere { <0.753191, 2.0659, 0>, 0.07412  texture { txt007 } }

cone {
    <0.753191, 2.0659, 0>, 0.07412,
    <0.465497, 2.76438, 0.791951>, 0.07412 open
    texture { txt007 }
}

sphere { <0.465497, 2.76438, 0.791951>, 0.07412  texture { txt007 } }

cone {
    <0.465497, 2.76438, 0.791951>, 0.07412,
    <-0.465497, 3.25383, 0.489453>, 0.07412 open
    texture { txt007 }
}

sphere { <-0.465497, 3.25383, 0.489453>, 0.07412  texture { txt007 } }

cone {
    <-0.465497, 3.25383, 0.489453>, 0.07412,
    <-0.753191, 2.85785, -0.489453>, 0.07412 open
    texture { txt007 }
}

sphere { <-0.753191, 2.85785, -0.489453>, 0.07412  texture { txt007 } }

cone {
    <-0.753191, 2.85785, -0.489453>, 0.07412,
    <-5.55112e-16, 2.12367, -0.791951>, 0.07412 open
    texture { txt007 }
}

sphere { <-5.55112e-16, 2.12367, -0.791951>, 0.07412  texture { txt007 } }

