// A `--sun split` bake's area lights (a studio's lamps, soft boxes: the lights of sun.json
// with `rect_light`) in Babylon.js (9.35): each as a RectAreaLight, and a patch of
// PBRMaterial's area-light specular so that it is shaded as splitsum's preview shades an
// area light. An ES module that takes the BABYLON namespace as a parameter, so that it
// serves the UMD build (`<script src="babylon.js">`, window.BABYLON) and the ES modules
// (`import * as BABYLON from '@babylonjs/core'`) alike.
//
//   import { compensateRectAreaLights, directionalLightFromSun, rectAreaLightFromSun } from './splitsum-babylon.js';
//   compensateRectAreaLights(BABYLON);   // before the first material lit by one compiles
//   const sun = await (await fetch('sky/sun.json')).json();
//   for (const l of [sun, ...sun.additional_lights]) {
//     if (l.rect_light) rectAreaLightFromSun(BABYLON, scene, l);   // a studio's lamp
//     else directionalLightFromSun(BABYLON, scene, l);             // a sun
//   }
//
// Babylon fetches its LTC tables (areaLightsLTC.bin) from assets.babylonjs.com through
// Tools.GetAssetUrl the first time a scene gets an area light (Lights/areaLight.pure.ts);
// a page without that host sets BABYLON.Tools.AssetBaseUrl to where it serves them.

/**
 * A light of a splitsum sun.json (the sun, or an entry of its additional_lights) as a
 * BABYLON.DirectionalLight of the same irradiance: Babylon shades a directional light of
 * colour c and intensity I with the irradiance c·I on a surface facing it, in the units of
 * its environment's radiance (× scene.environmentIntensity where it scales the .env), so
 * the light is `illuminance` (E's luminance) in intensity and E / illuminance in colour.
 * It shines from `direction` toward the origin and sits `distance` away (its shadow map's
 * camera: `new BABYLON.ShadowGenerator(2048, light)`).
 * @param {object} BABYLON - the Babylon.js namespace.
 * @param {BABYLON.Scene} scene
 * @param {object} light - sun.json, or an entry of its additional_lights.
 * @param {{distance?: number}} options
 * @returns {BABYLON.DirectionalLight}
 */
export function directionalLightFromSun(BABYLON, scene, light, { distance = 50 } = {}) {
  const sun = new BABYLON.DirectionalLight('splitsum sun', new BABYLON.Vector3(...light.direction.map((c) => -c)), scene);
  const colour = new BABYLON.Color3(...light.irradiance.map((c) => (light.illuminance > 0 ? c / light.illuminance : 0)));
  sun.diffuse = colour;
  sun.specular = colour.clone();
  sun.intensity = light.illuminance;
  sun.position = new BABYLON.Vector3(...light.direction.map((c) => distance * c));
  return sun;
}

/**
 * An area light of a splitsum sun.json (a light with `rect_light`: a studio's lamp or soft
 * box) as a BABYLON.RectAreaLight: the rectangle facing the origin from `distance` away
 * along `direction`, 2·distance·tan(half_width_deg) wide along `width_axis` and
 * 2·distance·tan(half_height_deg) high along `height_axis`, of the uniform radiance
 * `rect_light.radiance` (in the environment's units), which gives the origin the light's
 * irradiance. A point p away from the origin sees it off by about 2·(p·direction)/distance
 * in irradiance, so keep `distance` well beyond the scene. RectAreaLight casts no shadows.
 *
 * Orientation: a RectAreaLight has no rotation of its own; it spans its width along x and
 * its height along y of its parent's frame (RectAreaLight.transferToEffect hands the
 * parent's world matrix applied to the position, width and height to the shader as
 * vLightData, vLightWidth / 2, vLightHeight / 2) and shines from its −z side only
 * (ltcHelperFunctions' LTCEvaluate: nothing where cross(v1, v2)·(P − corner) < 0). So the
 * light is parented to a TransformNode (`light.parent`) that turns x, y, z to
 * height_axis × direction, height_axis, direction (x is width_axis up to its sign, which a
 * rectangle does not see), and sits at z = distance in it.
 *
 * Units: PBRMaterial shades the light's diffuse as diffuse × intensity × the LTC integral
 * (the rectangle's form factor: Lambert's), but as Babylon ships it its specular as
 * s·(s·t2.x·F0 + (1 − s)·t2.y·F90) × the LTC lobe's integral with s = specular × intensity
 * (pbrDirectLightingFunctions' computeAreaSpecularLighting): the light's colour in the place
 * of the surface's F0, linear in the radiance only at s = 1. So diffuse, specular and
 * intensity stay 1 and the radiance is a 1×1 float `emissionTexture` (light.emissionTexture,
 * a RawTexture: update it to scale the light), which scales both terms alike
 * (LTCEvaluateWithEmission). With compensateRectAreaLights the specular is linear in
 * specular × intensity too, and the light stays right.
 *
 * Babylon's sources relied on (packages/dev/core/src/): Lights/rectAreaLight.pure.ts,
 * Lights/areaLight.pure.ts, Shaders/ShadersInclude/ltcHelperFunctions.fx,
 * lightFragment.fx, pbrDirectLightingFunctions.fx, pbrDirectLightingSetupFunctions.fx.
 * @param {object} BABYLON - the Babylon.js namespace.
 * @param {BABYLON.Scene} scene
 * @param {object} light - sun.json, or an entry of its additional_lights, with rect_light.
 * @param {{distance?: number}} options
 * @returns {BABYLON.RectAreaLight} its parent (`light.parent`) the TransformNode of its frame,
 *   its `emissionTexture` the radiance; dispose those with it.
 */
export function rectAreaLightFromSun(BABYLON, scene, light, { distance = 100 } = {}) {
  const rect = light.rect_light;
  if (!rect) throw new Error('rectAreaLightFromSun: this light has no rect_light (a directional light: a BABYLON.DirectionalLight of its irradiance)');
  const B = BABYLON;
  const tan = (deg) => Math.tan((deg * Math.PI) / 180);
  const z = new B.Vector3(...light.direction).normalize();
  const y = new B.Vector3(...rect.height_axis).normalize();
  const frame = new B.TransformNode('splitsum area light frame', scene);
  frame.rotationQuaternion = B.Quaternion.RotationQuaternionFromAxis(B.Vector3.Cross(y, z), y, z);
  frame.computeWorldMatrix(true);
  const area = new B.RectAreaLight('splitsum area light', new B.Vector3(0, 0, distance), 2 * distance * tan(rect.half_width_deg), 2 * distance * tan(rect.half_height_deg), scene);
  area.parent = frame;
  area.emissionTexture = B.RawTexture.CreateRGBATexture(
    new Float32Array([...rect.radiance, 1]), 1, 1, scene, false, false,
    B.Constants.TEXTURE_NEAREST_SAMPLINGMODE, B.Constants.TEXTURETYPE_FLOAT,
  );
  return area;
}

// Babylon 9.35's GLSL as it ships (BABYLON.ShaderStore.IncludesShadersStore): the area
// light's specular in lightFragment, Babylon's Fresnel for a punctual light in the same
// include (the exact BRDF below uses it), and the end of computeAreaSpecularLighting in
// pbrDirectLightingFunctions, after which the functions of the patch go.
const AREA_SPECULAR = 'info.specular=computeAreaSpecularLighting(preInfo,light{X}.vLightSpecular.rgb,clearcoatOut.specularEnvironmentR0,reflectivityOut.colorReflectanceF90);';
const PUNCTUAL_FRESNEL = 'coloredFresnel=fresnelSchlickGGX(preInfo.VdotH,clearcoatOut.specularEnvironmentR0,reflectivityOut.colorReflectanceF90);';
const PUNCTUAL_FRESNEL_OPENPBR = '{vec3 metalFresnel=reflectivityOut.specularWeight*getF82Specular(preInfo.VdotH,clearcoatOut.specularEnvironmentR0,reflectivityOut.colorReflectanceF90,reflectivityOut.roughness);vec3 dielectricFresnel=fresnelSchlickGGX(preInfo.VdotH,reflectivityOut.dielectricColorF0,reflectivityOut.colorReflectanceF90);coloredFresnel=mix(dielectricFresnel,metalFresnel,reflectivityOut.metallic);}';
const AREA_SPECULAR_FUNCTION = 'vec3 computeAreaSpecularLighting(preLightingInfo info,vec3 specularColor,vec3 reflectance0,vec3 reflectance90) {vec3 fresnel=specularColor*info.areaLightFresnel.x*reflectance0+( vec3( 1.0 )-specularColor )*info.areaLightFresnel.y*reflectance90;return specularColor*fresnel*info.areaLightSpecular;}';
// What marks a patched include.
const MARK = 'splitsumAreaSpecularLighting';

// After computeAreaSpecularLighting (pbrDirectLightingFunctions, inside its #if
// defined(AREALIGHTUSED) && defined(AREALIGHTSUPPORTED) and #ifdef SPECULARTERM).
const FUNCTIONS = `
// splitsum (js/splitsum-babylon.js, compensateRectAreaLights): the LTC as a control variate,
// as splitsum's preview shades an area light (src/plan/ltc.rs, shade_polygon).
// The direction to the rectangle's centre as a directional light's pre-lighting info
// (computeDirectionalPreLightingInfo: lightData.xyz is the direction the light travels),
// the rest (NdotV, roughness, ...) as the area light's.
preLightingInfo splitsumAreaCentrePreLightingInfo(preLightingInfo info,vec3 V,vec3 N,vec3 P,vec3 lightPos) {preLightingInfo c=computeDirectionalPreLightingInfo(vec4(P-lightPos,0.0),V,N);c.NdotV=info.NdotV;c.attenuation=1.0;c.roughness=info.roughness;c.diffuseRoughness=info.diffuseRoughness;c.surfaceAlbedo=info.surfaceAlbedo;
#ifdef IRIDESCENCE
c.iridescenceIntensity=info.iridescenceIntensity;
#endif
return c;}
// spec = F·(the LTC over the rectangle) + β·(the exact BRDF at its centre × n·l × Ω − F·(the
// LTC's density there) × Ω), β = 4πα² / (4πα² + Ω), Ω the rectangle's solid angle, F the
// LTC's Fresnel F0·t2.x + (F90 − F0)·t2.y; "point" is Babylon's computeSpecularLighting at
// the centre (its GGX, visibility and Fresnel, × n·l × radiance), "radiance" the light's
// there (its emission texture's centre), info.areaLightSpecular Babylon's LTC integral
// (× the emission texture) and info.areaLightFresnel its t2.
vec3 splitsumAreaSpecularLighting(preLightingInfo info,preLightingInfo centre,vec3 point,vec3 radiance,sampler2D ltc1,vec3 V,vec3 N,vec3 P,vec3 lightPos,vec3 halfWidth,vec3 halfHeight,float roughness,float pointRoughness,vec3 reflectance0,vec3 reflectance90) {vec3 rectCoords[4];rectCoords[0]=lightPos+halfWidth-halfHeight;rectCoords[1]=lightPos-halfWidth-halfHeight;rectCoords[2]=lightPos-halfWidth+halfHeight;rectCoords[3]=lightPos+halfWidth+halfHeight;
// One-sided as LTCEvaluate.
if (dot(cross(rectCoords[1]-rectCoords[0],rectCoords[3]-rectCoords[0]),P-rectCoords[0])<0.0) return vec3(0.0);
// The solid angle: two spherical triangles (Van Oosterom and Strackee 1983).
vec3 p0=normalize(rectCoords[0]-P);vec3 p1=normalize(rectCoords[1]-P);vec3 p2=normalize(rectCoords[2]-P);vec3 p3=normalize(rectCoords[3]-P);float omega=2.0*atan(abs(dot(p0,cross(p1,p2))),1.0+dot(p0,p1)+dot(p1,p2)+dot(p2,p0))+2.0*atan(abs(dot(p0,cross(p2,p3))),1.0+dot(p0,p2)+dot(p2,p3)+dot(p3,p0));
// The LTC's density at the centre, in LTCEvaluate's frame and matrix: D_o(M^-1 c / |M^-1 c|) |det M^-1| / |M^-1 c|^3.
vec2 uv=LTCUv(N,V,roughness);vec4 t1=texture2D(ltc1,uv);mat3 mInv=mat3(vec3(t1.x,0,t1.y),vec3(0,1,0),vec3(t1.z,0,t1.w));vec3 T1=normalize(V-N*dot(V,N));vec3 T2=-cross(N,T1);vec3 o=mInv*(transposeMat3(mat3(T1,T2,N))*centre.L);float len=length(o);float density=max(o.z/len,0.0)*RECIPROCAL_PI*abs(t1.x*t1.w-t1.y*t1.z)/(len*len*len);
vec3 fresnel=reflectance0*info.areaLightFresnel.x+(reflectance90-reflectance0)*info.areaLightFresnel.y;float alphaG=convertRoughnessToAverageSlope(pointRoughness);float lobe=4.0*PI*alphaG*alphaG;float beta=lobe/(lobe+omega);vec3 exact=centre.NdotLUnclamped>0.0 ? point*omega : vec3(0.0);return max(fresnel*info.areaLightSpecular+beta*(exact-fresnel*radiance*(density*omega)),vec3(0.0));}
`;

// In place of AREA_SPECULAR (lightFragment, the PBR branch of an area light {X}): Babylon's
// punctual Fresnel at the centre (as PUNCTUAL_FRESNEL and PUNCTUAL_FRESNEL_OPENPBR), its
// computeSpecularLighting there, and the control variate, × the light's specular colour
// (specular × intensity, linearly).
const COMPENSATED = `{// splitsum (js/splitsum-babylon.js, compensateRectAreaLights): the LTC as a control variate.
preLightingInfo splitsumCentre=splitsumAreaCentrePreLightingInfo(preInfo,viewDirectionW,normalW,vPositionW,light{X}.vLightData.xyz);vec3 splitsumFresnel;
#if (CONDUCTOR_SPECULAR_MODEL==CONDUCTOR_SPECULAR_MODEL_OPENPBR)
{vec3 metalFresnel=reflectivityOut.specularWeight*getF82Specular(splitsumCentre.VdotH,clearcoatOut.specularEnvironmentR0,reflectivityOut.colorReflectanceF90,reflectivityOut.roughness);vec3 dielectricFresnel=fresnelSchlickGGX(splitsumCentre.VdotH,reflectivityOut.dielectricColorF0,reflectivityOut.colorReflectanceF90);splitsumFresnel=mix(dielectricFresnel,metalFresnel,reflectivityOut.metallic);}
#else
splitsumFresnel=fresnelSchlickGGX(splitsumCentre.VdotH,clearcoatOut.specularEnvironmentR0,reflectivityOut.colorReflectanceF90);
#endif
vec3 splitsumRadiance=vec3(1.0);
#if defined(RECTAREALIGHTEMISSIONTEXTURE{X})
splitsumRadiance=texture2DLodEXT(rectAreaLightEmissionTexture{X},vec2(0.5),0.0).rgb;
#endif
vec3 splitsumPoint=computeSpecularLighting(splitsumCentre,normalW,clearcoatOut.specularEnvironmentR0,splitsumFresnel,AARoughnessFactors.x,splitsumRadiance);info.specular=light{X}.vLightSpecular.rgb*${MARK}(preInfo,splitsumCentre,splitsumPoint,splitsumRadiance,areaLightsLTC1Sampler,viewDirectionW,normalW,vPositionW,light{X}.vLightData.xyz,light{X}.vLightWidth.xyz,light{X}.vLightHeight.xyz,roughness,max(roughness,AARoughnessFactors.x),clearcoatOut.specularEnvironmentR0,reflectivityOut.colorReflectanceF90);}`;

/**
 * Shades Babylon's RectAreaLight on a PBRMaterial as splitsum's preview shades an area
 * light, with the BRDF Babylon's punctual lights have. Babylon 9.35 shades an area light's
 * specular from its LTC table alone (the GGX fit of Heitz et al., 8–10 % off the GGX lobe
 * at r ≥ 0.35, tests/ltc.rs), with a Fresnel that takes the light's specular colour for the
 * surface's F0. This patches two WebGL2 GLSL includes of BABYLON.ShaderStore
 * .IncludesShadersStore (packages/dev/core/src/Shaders/ShadersInclude/*.fx; in the npm
 * package, in babylon.js's shader store): in `lightFragment` the area light's
 * `info.specular=computeAreaSpecularLighting(…)` becomes the LTC as a control variate, spec
 * = L·(F·LTC over the rectangle) + β·(f(c)·(n·c)·Ω·L − F·D_LTC(c)·Ω·L), where c is the
 * direction to the rectangle's centre, Ω its solid angle, β = 4πα² / (4πα² + Ω) (α =
 * r² + 0.0005, Babylon's convertRoughnessToAverageSlope), f(c)·(n·c) Babylon's own
 * computeSpecularLighting (its GGX, its height-correlated or fast visibility and its
 * punctual Fresnel, fresnelSchlickGGX(v·h, F0, F90), as for a DirectionalLight), F =
 * F0·t2.x + (F90 − F0)·t2.y the table's Fresnel with the material's F0 and F90, D_LTC(c)
 * the LTC's density at c, and L the light's radiance (its emissionTexture's centre, else 1)
 * × its specular × intensity; `pbrDirectLightingFunctions` gets the functions that does.
 * The multiple-scattering factor (pbrBlockFinalLitComponents, on the sum of the lights'
 * specular) and the diffuse are as they were. The WebGPU (WGSL) includes are left as they
 * are.
 *
 * Call it before the first material lit by an area light compiles: an engine keeps every
 * effect it compiled by shader name and defines (engine._compiledEffects), and a material
 * compiled before the patch keeps Babylon's shading until the engine's effects are released
 * (engine.releaseEffects()) and the material is rebuilt. It is idempotent, and throws where
 * the includes are not Babylon 9.35's.
 * @param {object} BABYLON - the Babylon.js namespace.
 * @returns {boolean} true where it patched now, false where it had already.
 */
export function compensateRectAreaLights(BABYLON) {
  const store = BABYLON.ShaderStore?.IncludesShadersStore ?? BABYLON.Effect?.IncludesShadersStore;
  const light = store?.lightFragment, functions = store?.pbrDirectLightingFunctions;
  if (typeof light === 'string' && typeof functions === 'string' && light.includes(MARK) && functions.includes(MARK)) return false;
  const missing = [
    ['lightFragment', light, AREA_SPECULAR],
    ['lightFragment', light, PUNCTUAL_FRESNEL],
    ['lightFragment', light, PUNCTUAL_FRESNEL_OPENPBR],
    ['pbrDirectLightingFunctions', functions, AREA_SPECULAR_FUNCTION],
  ].filter(([, text, want]) => typeof text !== 'string' || text.split(want).length !== 2);
  if (missing.length > 0) {
    throw new Error(
      `compensateRectAreaLights: this Babylon.js's GLSL includes are not 9.35's (${missing.map(([name, , want]) => `${name} lacks ${want.slice(0, 60)}…`).join('; ')}); ` +
        'leave its RectAreaLights as Babylon shades them (their specular then the LTC fit alone)',
    );
  }
  store.pbrDirectLightingFunctions = functions.replace(AREA_SPECULAR_FUNCTION, () => AREA_SPECULAR_FUNCTION + FUNCTIONS);
  store.lightFragment = light.replace(AREA_SPECULAR, () => COMPENSATED);
  return true;
}
