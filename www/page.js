// What the demo's two pages share: the message line, and drag and drop of files anywhere on the
// page.

/**
 * Shows `dropZone` while files are dragged over the window and hands the dropped FileList to
 * `onFiles`. Enter and leave events also fire for every child element crossed, so a depth count
 * (not the last event) says whether the drag is still over the page.
 */
export function attachDropZone(dropZone, onFiles) {
  const hasFiles = (event) => [...(event.dataTransfer?.types ?? [])].includes('Files');
  let depth = 0;
  window.addEventListener('dragenter', (event) => {
    if (!hasFiles(event)) return;
    event.preventDefault();
    depth++;
    dropZone.hidden = false;
  });
  window.addEventListener('dragover', (event) => hasFiles(event) && event.preventDefault());
  window.addEventListener('dragleave', (event) => {
    if (!hasFiles(event)) return;
    depth = Math.max(0, depth - 1);
    if (depth === 0) dropZone.hidden = true;
  });
  window.addEventListener('drop', (event) => {
    event.preventDefault();
    depth = 0;
    dropZone.hidden = true;
    onFiles(event.dataTransfer?.files);
  });
}

/**
 * Shows `text` in the page's `#message` line; `kind` 'error' makes it an alert and mirrors it in
 * `data-error` on the root element (the end-to-end tests read it), 'notice' styles it apart.
 */
export function showMessage(text, kind = '') {
  const message = document.getElementById('message');
  message.textContent = text;
  message.className = kind;
  message.setAttribute('role', kind === 'error' ? 'alert' : 'status');
  const root = document.documentElement;
  if (kind === 'error') root.dataset.error = text;
  else delete root.dataset.error;
}
