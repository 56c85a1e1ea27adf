// whitted.pov -- POV-Ray 3.7 twin of Glint's assets/scenes/whitted.toml
//
// WHAT THIS IS
//   The built-in Glint scene "whitted" (Whitted 1980, fig. 1: a glass sphere in
//   front of a mirror sphere over a red/yellow checkered floor, one point light,
//   blue background) restated in POV-Ray's scene language, so that POV-Ray's
//   wall time can be measured next to Glint's on the same machine.  It is meant
//   for timing only: it reproduces the geometry, camera, light and the Whitted
//   (Phong + mirror + refraction) shading terms as closely as POV-Ray's model
//   allows, but it is not a pixel-exact reference.
//
//   Written for Glint (not taken from elsewhere), like embree_rays.cpp beside it: the anchor
//   of the Whitted benchmark, timed against Glint in one session on one machine. Not part
//   of any build. Debian: apt-get install povray. One sample a pixel, 2 threads, no window:
//     povray +Icrates/glint-core/benches/whitted.pov +O/tmp/pov.png +W1280 +H720 -A +WT2 -D -V +FN
//     glint render whitted --width 1280 --height 720 --spp 1 --depth 5 --bailout 0 --threads 2 -o /tmp/glint.png
//   (File_Gamma=sRGB may be added but is what POV-Ray 3.7.0 writes already.) On 2026-12-04 the
//   two images differed in 353 of 921,600 pixels, on the horizon's sub-pixel checkers and at
//   the glass sphere's rim.

// HOW GLINT'S TERMS MAP ONTO POV-RAY'S
//   Glint, per hit and channel (docs/scene-format.md):
//     I = Ia*ka*T + V*( Id*kd*T*max(N.L,0) + Is*ks*max(N.H,0)^n ) + kr*Ir + kt*It
//   (T = checker colour, V = shadow visibility, no light attenuation by default).
//
//   Ia (world.ambient 0.15)  -> global_settings ambient_light rgb 0.15.
//   ka                       -> finish ambient ka.  POV multiplies ambient by the
//                               pigment colour and by ambient_light, so with the
//                               checker as the pigment this is exactly Ia*ka*T.
//   kd (and checker colours) -> pigment = the kd colour(s), finish diffuse 1
//                               for the floor; for the mirror (kd = 0.05 grey)
//                               pigment white with diffuse 0.05 / ambient 0.05.
//                               brilliance is left at 1, i.e. plain N.L.
//   ks, shininess n          -> finish "specular ks roughness 1/n".  POV's
//                               specular highlight is the Blinn half-vector lobe
//                               (N.H)^(1/roughness), which is exactly Glint's
//                               default specular_model = "blinn".  POV's "phong"
//                               keyword is the R.V lobe instead, which would be
//                               Glint's specular_model = "phong" and gives a
//                               different (wider) highlight for the same n, so
//                               it is not used.
//   kr                       -> finish reflection { kr } (constant: no fresnel,
//                               no falloff, no metallic), i.e. kr*Ir.
//   kt, ior                  -> pigment transmit kt on a white colour plus
//                               interior { ior }.  POV scales the refracted ray
//                               by the pigment's rgb*filter + transmit = kt,
//                               so this is kt*It.  Transmit (not filter) is used
//                               because the glass is colourless; with a white
//                               pigment both give the same number.
//   Shadows through glass    -> POV attenuates shadow rays by the same
//                               rgb*filter + transmit factor at every surface
//                               crossed, without bending them: kt per surface,
//                               kt^2 through the whole sphere -- Glint's rule.
//   point light, diffuse = specular = 1, no attenuation
//                            -> light_source colour rgb 1, no fade_distance /
//                               fade_power (POV's default is no attenuation,
//                               like Glint's default { c = 1, l = 0, q = 0 }).
//   background               -> background { rgb <0.15, 0.35, 0.85> }, seen by
//                               every ray that escapes, as in Glint.
//   checker { size = 1 }     -> POV's "checker" pattern on the y = 0 plane: unit
//                               squares aligned to the world origin, colour 1
//                               where floor(x) + floor(z) is even (Glint: kd),
//                               colour 2 where it is odd (Glint: checker.kd).
//   max depth 5              -> max_trace_level 6 (see "depth" below).
//   bailout 0                -> adc_bailout 0 (POV's default is 1/255).
//
// DEPTH
//   Glint: the camera ray's hit is depth 0 and may spawn children while
//   depth < max_depth, so --depth 5 = camera ray + 5 generations of secondary
//   rays.  POV-Ray refuses to trace a ray whose trace level (0 for the camera
//   ray, +1 per reflection/refraction) has reached max_trace_level, so
//   max_trace_level N = camera ray + N-1 generations.  Glint's depth 5 is
//   therefore POV's max_trace_level 6.  (With 5, POV would stop one bounce
//   earlier than Glint.)  Checked at 1280x720: max_trace_level 6 differs from
//   Glint --depth 5 in 353 pixels, max_trace_level 5 in 11,271 pixels (and
//   matches Glint --depth 4 to 341 pixels).
//
// WHERE THE TWO MODELS STILL DIFFER
//   - No fresnel anywhere (POV's reflection is constant unless "fresnel on" is
//     given; Glint's Whitted model has constant kr/kt too).
//   - Total internal reflection: Glint sends (kr + kt)*Ir = 0.98*Ir along the
//     mirror ray; POV sends the whole transmitted share as reflection at weight
//     1 (unfiltered) and skips the ordinary kr reflection there: 1.0*Ir.
//   - Ambient/diffuse of a transparent pigment are scaled by its opacity
//     (1 - transmit) in POV; harmless here because the glass has ka = kd = 0.
//     Specular highlights are not scaled by opacity in POV, as in Glint.
//   - Self-intersection: POV ignores hits closer than its own small epsilons
//     (MIN_ISECT_DEPTH, SHADOW_TOLERANCE 1e-3 for shadow rays); Glint offsets
//     ray origins (robust mode).  Only grazing edges can differ.
//   - POV skips a light where N.L is below a tiny epsilon, Glint where N.L <= 0.
//   - Camera rays: with -A POV's perspective camera shoots one ray per pixel
//     centre, as Glint does with spp 1, through the same image plane (see
//     camera); the pixel-for-pixel agreement of the two images confirms it.
//   - No photons, no radiosity, no media: POV's shadows through the glass are
//     straight kt-filtered shadows, never caustics, like Glint's.
//   - Output: Glint writes linear values clamped to [0,1] and sRGB-encoded.
//     With assumed_gamma 1 the colours below are linear, as Glint's are, and
//     POV 3.7's PNG output is sRGB-encoded (File_Gamma), so the 8-bit values
//     agree (checked: background, floor squares and shadows match exactly).
//   - Ray counting: POV increments its reflected/refracted counters (and its
//     "Rays" total) for the children of the deepest generation too, and only
//     then refuses them at the trace-level check without intersecting them;
//     Glint never creates those rays.  POV's "Shadow Ray Tests" counts one test
//     per segment (a shadow ray restarts after every transparent surface) and
//     counts shadow-cache hits; Glint counts one shadow ray per light per hit.

#version 3.7;

global_settings {
  assumed_gamma 1.0        // scene colours are linear, as in Glint
  max_trace_level 6        // = Glint --depth 5 (see DEPTH above)
  adc_bailout 0            // = Glint --bailout 0: trace every child ray
  ambient_light rgb 0.15   // Glint world.ambient
  // no radiosity, no photons
}

// Camera.
// Glint: position (0, 1.6, -5), look_at (0, 0.9, 0), fov_y = 45 deg, vertical.
// POV-Ray's "angle" is the HORIZONTAL field of view, so for a 16:9 image
//   angle = 2 * atan( tan(fov_y / 2) * width / height )
//         = 2 * atan( tan(22.5 deg) * 16/9 ) = 72.7344 deg
// (written below as that formula, so it stays right if fov_y changes).
// Handedness: Glint is right-handed with screen right = forward x up, which for
// a camera looking along +z with up +y is -x (the mirror sphere at x = +0.9 is
// on the LEFT of Glint's image).  POV-Ray is left-handed: its default
// "right x" puts +x on the right and would mirror the picture.  A negative
// right vector ("right -x * aspect") makes POV's camera right-handed, so the
// scene coordinates are used unchanged and the image is not mirrored.
#declare Glint_fov_y = 45;
#declare Aspect = image_width / image_height;   // 1280/720 = 16/9
camera {
  perspective
  location <0.0, 1.6, -5.0>
  up       y
  right    -x * Aspect
  angle    degrees(2 * atan(tan(radians(Glint_fov_y / 2)) * Aspect))
  look_at  <0.0, 0.9, 0.0>
}

background { rgb <0.15, 0.35, 0.85> }

// Point light: diffuse = specular = 1, no attenuation, hard shadows.
light_source { <-4.0, 7.0, -5.0> color rgb 1.0 }

// Checkered floor: ka 0.5 (times the square's colour), kd red / yellow, ks 0.
plane {
  y, 0
  texture {
    pigment { checker color rgb <0.9, 0.1, 0.1> color rgb <0.95, 0.9, 0.1> }
    finish { ambient 0.5 diffuse 1.0 specular 0 phong 0 reflection { 0 } }
  }
}

// Mirror sphere: ka 0.05, kd 0.05, ks 0.8, shininess 200, kr 0.85.
sphere {
  <0.9, 1.1, 1.6>, 1.1
  texture {
    pigment { color rgb 1 }
    finish {
      ambient 0.05
      diffuse 0.05
      specular 0.8 roughness 1/200
      phong 0
      reflection { 0.85 }
    }
  }
}

// Glass sphere: ka 0, kd 0, ks 0.8, shininess 300, kr 0.08, kt 0.9, ior 1.5.
sphere {
  <-0.5, 1.15, -1.2>, 0.75
  texture {
    pigment { color rgbt <1, 1, 1, 0.9> }
    finish {
      ambient 0
      diffuse 0
      specular 0.8 roughness 1/300
      phong 0
      reflection { 0.08 }
    }
  }
  interior { ior 1.5 }
}
