// The worker that createWorker() (worker.js) starts in browsers: subsurf's own functions.
import { expose, functions } from './worker-thread.js';

expose(functions);
