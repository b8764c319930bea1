// The thread that createWorker() (worker-node.js) starts in Node: subsurf's own functions.
import { parentPort } from 'node:worker_threads';
import { expose, functions } from './worker-thread.js';

expose(functions, parentPort);
