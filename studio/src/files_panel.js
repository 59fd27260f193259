// The files (examples) panel: every model under the root, with a thumbnail the server
// renders on demand. Thumbnails load one at a time, only when visible, so that they
// never hold up the live view.
const queue = [];
let loading = false;
let held = 0;  // derivations of the live view under way: thumbnails wait for them

// +1 when the live view asks for a picture, -1 when it has it.
export function holdThumbnails(change) {
  held = Math.max(0, held + change);
  next();
}

function next() {
  if (loading || held > 0 || !queue.length) return;
  loading = true;
  const img = queue.shift();
  img.onload = () => { loading = false; next(); };
  // A model that does not parse has no thumbnail: an empty box, not a broken image.
  img.onerror = () => { img.removeAttribute('src'); loading = false; next(); };
  img.dataset.requested = 'true';
  img.src = img.dataset.src;
}

const observer = new IntersectionObserver((entries) => {
  for (const e of entries) {
    if (!e.isIntersecting) continue;
    observer.unobserve(e.target);
    queue.push(e.target);
    next();
  }
});

// `thumbnails`: false on the static page, which has no server to draw them.
export function showFiles(files, open, thumbnails = true) {
  const list = document.getElementById('file-list');
  const rows = files.map((f) => {
    const row = document.createElement('div');
    row.className = 'file';
    row.dataset.path = f.path;
    row.title = f.path;
    const img = document.createElement('img');
    img.alt = '';
    if (thumbnails) {
      img.dataset.src = '/api/thumbnail?path=' + encodeURIComponent(f.path);
      observer.observe(img);
    } else {
      img.hidden = true;
    }
    const name = document.createElement('span');
    name.textContent = f.path.replace(/\.l$/, '');
    row.append(img, name);
    row.addEventListener('click', () => open(f.path));
    return row;
  });
  list.replaceChildren(...rows);
  document.getElementById('file-filter').addEventListener('input', (e) => {
    const q = e.target.value.toLowerCase();
    for (const row of rows) row.hidden = !row.dataset.path.toLowerCase().includes(q);
  });
}

export function markCurrent(path) {
  for (const row of document.querySelectorAll('#file-list .file'))
    row.classList.toggle('current', row.dataset.path === path);
}

// A saved or reloaded file gets a new thumbnail (the server renders it again) once the
// typing has paused: a thumbnail of a large model costs the server as much as a keystroke's
// picture, and one made at every save would slow the next keystroke down.
const refreshTimers = new Map();
export function refreshThumbnail(path, mtime) {
  clearTimeout(refreshTimers.get(path));
  refreshTimers.set(path, setTimeout(() => {
    refreshTimers.delete(path);
    const row = [...document.querySelectorAll('#file-list .file')].find((r) => r.dataset.path === path);
    const img = row?.querySelector('img');
    if (!img || !img.dataset.src) return;
    img.dataset.src = img.dataset.src.replace(/&v=\d+$/, '') + '&v=' + mtime;
    if (img.dataset.requested && !queue.includes(img)) { queue.push(img); next(); }
  }, 3000));
}
