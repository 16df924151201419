// The Web Worker that writes the .3dm (src/rhino.js): rhino3dm is loaded here,
// on the first export, and the file is written here, so that the page does not
// freeze while a large mesh's panels are added one by one.
import { rhinoFile } from './rhino.js';

self.onmessage = async ({ data }) => {
  try {
    self.postMessage({ bytes: await rhinoFile(data) });
  } catch (error) {
    self.postMessage({ error: error.message });
  }
};
