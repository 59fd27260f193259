// The files (examples) panel: every model under the root, with a thumbnail the server
// renders on demand. Thumbnails load one at a time, only when visible, so that they
// never hold up the live view.
const queue = [];
let loading = false;

function next() {
  if (loading || !queue.length) return;
  loading = true;
  const img = queue.shift();
  img.onload = img.onerror = () => { loading = false; next(); };
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

export function showFiles(files, open) {
  const list = document.getElementById('file-list');
  const rows = files.map((f) => {
    const row = document.createElement('div');
    row.className = 'file';
    row.dataset.path = f.path;
    row.title = f.path;
    const img = document.createElement('img');
    img.alt = '';
    img.dataset.src = '/api/thumbnail?path=' + encodeURIComponent(f.path);
    observer.observe(img);
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
