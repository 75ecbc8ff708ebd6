// POV-Ray 3.7's side of tests/test_sides.c's check of filtered shadows: scenes/shadows_filtered.rf
// written by hand. Transmit t and filter f pass (f colour + t) of the light at each surface a
// shadow ray crosses; with ior 1 the camera rays go straight through too. refray's ka Ia is
// POV-Ray's pigment x ambient x ambient_light, kd its pigment x diffuse.
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 5 adc_bailout 0 ambient_light 1 }
background { rgb <0, 0, 0> }
camera { perspective location <0, 0, 5> direction <0, 0, -1> right <2, 0, 0> up <0, 2, 0> }
light_source { <0, 4, 3> color rgb <1, 1, 1> }
plane { <0, 0, 1>, 0 texture { pigment { rgb <1, 1, 1> } finish { ambient 0.1 diffuse 0.5 } } }
sphere { <0, 2, 1.5>, 0.5
  texture { pigment { rgbt <0, 0, 0, 0.5> } finish { ambient 0 diffuse 0 } } interior { ior 1 } }
triangle { <-1.5, -0.2, 1>, <-0.5, -0.2, 1>, <-1, 0.8, 1.2>
  texture { pigment { rgbf <1, 0.5, 0.25, 1> } finish { ambient 0 diffuse 0 } } interior { ior 1 } }
