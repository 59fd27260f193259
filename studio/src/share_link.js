// A model shared as a link (the static page): its text compressed with deflate-raw and
// written in base64url after `#model=` in the address, so that the text never leaves the
// browser (a fragment is not sent to the server) and the link opens it.

const prefix = 'model=';

async function bytesThrough(stream, bytes) {
  const out = new Blob([bytes]).stream().pipeThrough(stream);
  return new Uint8Array(await new Response(out).arrayBuffer());
}

function base64url(bytes) {
  let s = '';
  for (let i = 0; i < bytes.length; i += 0x8000) s += String.fromCharCode(...bytes.subarray(i, i + 0x8000));
  return btoa(s).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
}

function fromBase64url(text) {
  const s = atob(text.replace(/-/g, '+').replace(/_/g, '/'));
  return Uint8Array.from(s, (c) => c.charCodeAt(0));
}

// The address that opens `text` under `name`.
export async function shareLink(text, name) {
  const packed = await bytesThrough(new CompressionStream('deflate-raw'), new TextEncoder().encode(text));
  const url = new URL(location.href);
  url.search = '';
  url.hash = prefix + base64url(packed) + '&name=' + encodeURIComponent(name);
  return url.href;
}

// {text, name} of a shared link's fragment, or null when the address shares nothing.
export async function sharedModel(hash = location.hash) {
  // The static page's index.html has decompressed the address's model already.
  const early = await globalThis.graftalBoot?.shared;
  if (early && early.hash === hash) return { text: early.text, name: early.name };
  const fragment = hash.replace(/^#/, '');
  if (!fragment.startsWith(prefix)) return null;
  const [data, ...rest] = fragment.slice(prefix.length).split('&');
  const name = new URLSearchParams(rest.join('&')).get('name') || 'shared.l';
  const bytes = await bytesThrough(new DecompressionStream('deflate-raw'), fromBase64url(data));
  return { text: new TextDecoder().decode(bytes), name };
}
