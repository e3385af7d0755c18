"""Imported only by the forkserver that LocalCluster worker processes are forked from
(engine.PRELOAD), never in the sweep's own process: it makes SIGINT ignored there, and
the forkserver hands that disposition to every worker it forks. Ctrl-C in a terminal
goes to the whole process group; the sweep's process alone then answers it (it closes
the cluster, keeps the table resumable and prints one line), instead of every worker
printing its own KeyboardInterrupt traceback (69 lines for two workers)."""

import signal

signal.signal(signal.SIGINT, signal.SIG_IGN)
