"""`batstudy.ShardTask`: one shard of a study as a task a cluster library runs, retries and
requeues (submitit, dask); docs/python.md, "Scaling out from Python"."""

from __future__ import annotations

import os
from typing import Any, Optional, Tuple, Union


class ShardTask:
    """Shard ``shard = (i, n)`` of ``study`` into ``output``, as a picklable callable that
    returns the shard file's path.

    Every call resumes what an earlier call of the same task left in ``output``
    (``resume=True``), so a retried or requeued task continues its shard instead of starting
    over. It is checkpointable for submitit: on a time-out or a pre-emption submitit's signal
    handler stops the run as Ctrl-C does (the points in flight finish and are kept), calls
    :meth:`checkpoint`, which hands back this task, and requeues it; the requeued job
    resumes the shard. ``jobs`` is the threads of the one ``run`` (give it the cores the
    scheduler granted the task; default: all the machine's)."""

    def __init__(
        self,
        study: Any,
        shard: Tuple[int, int],
        output: Union[str, "os.PathLike[str]"],
        jobs: Optional[int] = None,
    ) -> None:
        self.study = study
        self.shard = (int(shard[0]), int(shard[1]))
        self.output = os.fspath(output)
        self.jobs = jobs

    def __call__(self) -> str:
        from ._api import run

        return os.fspath(
            run(self.study, output=self.output, shard=self.shard, jobs=self.jobs, resume=True, progress=False)
        )

    def checkpoint(self, *args: Any, **kwargs: Any) -> Any:
        """submitit's hook: requeue this task as it is (its shard file holds the progress)."""
        from submitit.helpers import DelayedSubmission

        return DelayedSubmission(self)

    def __repr__(self) -> str:
        return f"ShardTask(shard={self.shard}, output={self.output!r})"
