// A correct irradiance that SwiftShader (headless Chromium's WebGL 2) computes wrongly, found by
// the page's grader (docs/web.md, "One correct file the page fails"): the file's
// irradianceAt, with radiance 1 in every direction (a 16x16 cube of ones), must give 1 for
// every normal; the desktop (Mesa) and the same sum in double give 1.001. The page prints
// what SwiftShader gives, then the same with the texel's exact solid angle replaced by its
// usual approximation h^2 / (1 + s^2 + t^2)^1.5.
//   node --experimental-websocket web/test/irradiance_repro.mjs
import fs from 'node:fs';
import os from 'node:os';
import path from 'node:path';

import {Chromium, serve} from './chromium.mjs';

const root = path.resolve(path.dirname(new URL(import.meta.url).pathname), '../..');
const exact = fs.readFileSync(
    path.join(root, 'tests/variants/irradiance/correct_exact_solid_angle.glsl'), 'utf8');
const approximate = exact.replace(
    /float omega = [^;]*;/s, 'float omega = h * h / pow(s * s + t * t + 1.0, 1.5);');
// The page's own GLSL ES header (core/shader/preprocess.cpp: #version, precisions, findMSB),
// so that the file compiles as the page's grader compiles it.
const header = /kEs300Header = R"\(([\s\S]*?)\)";/.exec(
    fs.readFileSync(path.join(root, 'core/shader/preprocess.cpp'), 'utf8'))[1];
const page = (body) => `<canvas id=c width=4 height=1></canvas>
<script>
window.run = () => {
  const gl = document.getElementById('c').getContext('webgl2');
  gl.getExtension('EXT_color_buffer_float');
  const vs = \`#version 300 es
  void main() { vec2 p = vec2((gl_VertexID & 1) * 4 - 1, (gl_VertexID & 2) * 2 - 1); gl_Position = vec4(p, 0, 1); }\`;
  const fs = \`${header}
const float PI = 3.14159265358979;
uniform samplerCube uEnvironment;
uniform vec3 uN[4];
out vec4 o;
${body}
void main() { o = vec4(irradianceAt(normalize(uN[int(gl_FragCoord.x)])), 1.0); }\`;
  const p = gl.createProgram();
  for (const [type, src] of [[gl.VERTEX_SHADER, vs], [gl.FRAGMENT_SHADER, fs]]) {
    const s = gl.createShader(type); gl.shaderSource(s, src); gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) return gl.getShaderInfoLog(s);
    gl.attachShader(p, s);
  }
  gl.linkProgram(p); gl.useProgram(p);
  const cube = gl.createTexture(); gl.activeTexture(gl.TEXTURE0); gl.bindTexture(gl.TEXTURE_CUBE_MAP, cube);
  const size = 16;
  gl.texStorage2D(gl.TEXTURE_CUBE_MAP, 1, gl.RGBA32F, size, size);
  const ones = new Float32Array(size * size * 4).fill(1);
  for (let f = 0; f < 6; ++f) gl.texSubImage2D(gl.TEXTURE_CUBE_MAP_POSITIVE_X + f, 0, 0, 0, size, size, gl.RGBA, gl.FLOAT, ones);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
  gl.texParameteri(gl.TEXTURE_CUBE_MAP, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
  gl.uniform1i(gl.getUniformLocation(p, 'uEnvironment'), 0);
  gl.uniform3fv(gl.getUniformLocation(p, 'uN'), [0, -1, 0, 0, 1, 0, 1, 0, 0, 0.3, -0.8, 0.2]);
  const tex = gl.createTexture(); gl.bindTexture(gl.TEXTURE_2D, tex);
  gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, 4, 1);
  const fb = gl.createFramebuffer(); gl.bindFramebuffer(gl.FRAMEBUFFER, fb);
  gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, tex, 0);
  gl.viewport(0, 0, 4, 1); gl.drawArrays(gl.TRIANGLE_STRIP, 0, 4);
  const out = new Float32Array(16); gl.readPixels(0, 0, 4, 1, gl.RGBA, gl.FLOAT, out);
  return Array.from(out).map((v) => v.toFixed(4)).join(' ');
};
</script>
`;
const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'pbrlab-irradiance-'));
fs.writeFileSync(path.join(dir, 'exact.html'), page(exact));
fs.writeFileSync(path.join(dir, 'approximate.html'), page(approximate));
const server = await serve(dir);
const browser = await Chromium.launch(path.join(dir, 'profile'));
const tab = await browser.newPage();
for (const name of ['exact', 'approximate']) {
  await tab.navigate(`http://127.0.0.1:${server.address().port}/${name}.html`);
  const values = (await tab.evaluate('run()')).split(' ').filter((v, i) => i % 4 === 0);
  console.log(`${name} solid angle: E / pi for N = -y, +y, +x, (0.3, -0.8, 0.2): ${values.join(' ')} (expected 1.001)`);
}
await browser.close();
server.close();
fs.rmSync(dir, {recursive: true, force: true});
