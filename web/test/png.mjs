// Reading the 8-bit PNG files the two renderers write (libpng's on the desktop, stb's in the
// page) and comparing two pictures, with Node's zlib only.
import zlib from 'node:zlib';

// Non-interlaced 8-bit grey, RGB or RGBA: what `pbrlab render --out x.png` and the page write.
export function decodePng(bytes) {
  if (bytes.readUInt32BE(0) !== 0x89504e47) throw new Error('not a PNG file');
  let offset = 8, width = 0, height = 0, channels = 0;
  const data = [];
  while (offset < bytes.length) {
    const length = bytes.readUInt32BE(offset);
    const type = bytes.toString('latin1', offset + 4, offset + 8);
    const body = bytes.subarray(offset + 8, offset + 8 + length);
    if (type === 'IHDR') {
      width = body.readUInt32BE(0);
      height = body.readUInt32BE(4);
      const [depth, colour, , , interlace] = body.subarray(8, 13);
      channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour];
      if (depth !== 8 || !channels || interlace) throw new Error('not an 8-bit, non-interlaced PNG');
    } else if (type === 'IDAT') {
      data.push(body);
    }
    offset += 12 + length;
  }
  const raw = zlib.inflateSync(Buffer.concat(data));
  const stride = width * channels;
  const pixels = new Uint8Array(stride * height);
  for (let y = 0; y < height; ++y) {
    const filter = raw[y * (stride + 1)];
    const row = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
    for (let i = 0; i < stride; ++i) {
      const a = i >= channels ? pixels[y * stride + i - channels] : 0;
      const b = y > 0 ? pixels[(y - 1) * stride + i] : 0;
      const c = i >= channels && y > 0 ? pixels[(y - 1) * stride + i - channels] : 0;
      const p = a + b - c;
      const paeth = Math.abs(p - a) <= Math.abs(p - b) && Math.abs(p - a) <= Math.abs(p - c)
          ? a : Math.abs(p - b) <= Math.abs(p - c) ? b : c;
      const predicted = [0, a, b, (a + b) >> 1, paeth][filter];
      pixels[y * stride + i] = (row[i] + predicted) & 255;
    }
  }
  return {width, height, channels, pixels};
}

// How far the page's picture may be from the desktop's, in 8-bit display codes. Each renderer
// rounds its own float arithmetic (SwiftShader, llvmpipe), then its own display encoding: most
// pixels differ by a code or none; a few differ more, on silhouettes (coverage decided by the
// last bit of a rasterizer) and, for the GPU estimators, where a sample reads a small mip.
// Measured on all 21 steps (docs/web.md): the mean difference is 0.000-0.25 codes, and the
// pixels more than 3 codes off are 0.000-0.06% of the picture but for the estimators that
// read the environment's mips: brdf_lut 0.23%, split_sum 0.16%, mc_specular 0.68%,
// prefilter 0.75%. A wrong picture (a texture read as sRGB that is linear, a failed upload)
// was 49-100% off.
export const kPictureTolerance = {
  codes: 3,                 // a pixel "differs" when a channel is more than this many codes off
  differingFraction: 0.01,  // at most this fraction of the pixels may differ
};

export function comparePictures(native, web) {
  if (native.width !== web.width || native.height !== web.height)
    return {passes: false, describe: `sizes differ: ${native.width}x${native.height} and ` +
                                     `${web.width}x${web.height}`};
  let worst = 0, differing = 0, sum = 0;
  const n = native.width * native.height;
  const channels = Math.min(3, native.channels, web.channels);
  for (let p = 0; p < n; ++p) {
    let d = 0;
    for (let c = 0; c < channels; ++c)
      d = Math.max(d, Math.abs(native.pixels[p * native.channels + c] -
                               web.pixels[p * web.channels + c]));
    worst = Math.max(worst, d);
    sum += d;
    if (d > kPictureTolerance.codes) ++differing;
  }
  const fraction = differing / n;
  return {
    passes: fraction <= kPictureTolerance.differingFraction,
    worst, meanCodes: sum / n, differingFraction: fraction,
    describe: `mean ${(sum / n).toFixed(3)} codes, worst ${worst}, ` +
              `${(100 * fraction).toFixed(3)}% of pixels more than ${kPictureTolerance.codes} off`,
  };
}
