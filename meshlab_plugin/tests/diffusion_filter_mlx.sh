# shellcheck shell=bash
# Sourced by headless_test.sh and scripts/meshlab-screenshot.sh: one place for the parameters of
# "Surface diffusion N steps" in a meshlabserver filter script.
#   diffusion_filter_mlx STEPS AUTOMATIC_TAU TAU BETA CONSERVE_VOLUME FIXED_BOUNDARY RETRIANGULATE
#                        EDGE_LENGTH CURVATURE MASS EXTRAPOLATE
# prints the <filter> element with every parameter (meshlabserver asserts on a missing one).
# CURVATURE and MASS are indices of the choices (0: the defaults); an enum parameter needs its
# choices in the script, or meshlabserver drops it and aborts as on a missing one.
#   anisotropic_filter_mlx ENERGY G FORMULA, then the eleven above
# prints "Anisotropic surface diffusion N steps" with the same and the surface energy's: ENERGY an
# index of isotropic, ellipsoidal, sum, formula; G numbers separated by commas.
#   substrate_filter_mlx Z CONTACT_ANGLE MOBILITY ENERGY G FORMULA, then the eleven above
# prints "Surface diffusion on a substrate N steps": the anisotropic filter's parameters less
# FixedBoundary (FIXED_BOUNDARY is not written) and the substrate's.
diffusion_filter_mlx() {
  printf ' <filter name="Surface diffusion N steps">\n'
  diffusion_parameters_mlx "$@"
  printf ' </filter>\n'
}

anisotropic_filter_mlx() {
  printf ' <filter name="Anisotropic surface diffusion N steps">\n'
  diffusion_parameters_mlx "${@:4}"
  cat <<MLX
  <Param type="RichEnum" name="Energy" value="$1" enum_cardinality="4" enum_val0="isotropic" enum_val1="ellipsoidal"
         enum_val2="sum" enum_val3="formula"/>
  <Param type="RichString" name="EnergyG" value="$2"/>
  <Param type="RichString" name="EnergyFormula" value="$3"/>
 </filter>
MLX
}

substrate_filter_mlx() {
  printf ' <filter name="Surface diffusion on a substrate N steps">\n'
  diffusion_parameters_mlx "${@:7}" | grep -v '"FixedBoundary"'
  cat <<MLX
  <Param type="RichFloat" name="SubstrateZ" value="$1"/>
  <Param type="RichFloat" name="ContactAngle" value="$2"/>
  <Param type="RichFloat" name="ContactLineMobility" value="$3"/>
  <Param type="RichEnum" name="Energy" value="$4" enum_cardinality="4" enum_val0="isotropic" enum_val1="ellipsoidal"
         enum_val2="sum" enum_val3="formula"/>
  <Param type="RichString" name="EnergyG" value="$5"/>
  <Param type="RichString" name="EnergyFormula" value="$6"/>
 </filter>
MLX
}

diffusion_parameters_mlx() {
  cat <<MLX
  <Param type="RichInt" name="Steps" value="$1"/>
  <Param type="RichBool" name="AutomaticTau" value="$2"/>
  <Param type="RichFloat" name="Tau" value="$3"/>
  <Param type="RichFloat" name="Beta" value="$4"/>
  <Param type="RichBool" name="ConserveVolume" value="$5"/>
  <Param type="RichBool" name="FixedBoundary" value="$6"/>
  <Param type="RichBool" name="Retriangulate" value="$7"/>
  <Param type="RichFloat" name="EdgeLength" value="$8"/>
  <Param type="RichEnum" name="Curvature" value="$9" enum_cardinality="3" enum_val0="cotangent"
         enum_val1="normal_integral" enum_val2="normal_integral_angle_sum"/>
  <Param type="RichEnum" name="Mass" value="${10}" enum_cardinality="2" enum_val0="voronoi" enum_val1="volume_gradient"/>
  <Param type="RichBool" name="Extrapolate" value="${11}"/>
MLX
}
