// Drag and drop of files anywhere on a page, shared by the demo's two pages.

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
