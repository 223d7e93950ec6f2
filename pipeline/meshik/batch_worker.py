"""One batch job in its own process: `python -m meshik.batch_worker SPEC_JSON`.

SPEC_JSON: {"constraints": path, "destination": folder, "options": pose_job keyword arguments,
"result": path}. Writes [status, reason, frames] as JSON to the result path: status "done",
"skipped" or "failed" (reason: the error message). A process that dies writes nothing; the
batch runner then reports its exit status.
"""
import json
import signal
import sys


def main(spec_text: str) -> int:
    """Run the job described by the JSON spec; always 0 once the result is written."""
    from meshik.pipeline import pose_job

    # terminate() from the batch runner: unwind normally so the job discards its staging folder
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(128 + signal.SIGTERM))
    spec = json.loads(spec_text)
    try:
        report = pose_job(spec["constraints"], spec["destination"], quiet=True, **spec["options"])
        result = ["skipped" if report.get("skipped") else "done", None, report.get("frame_count", 0)]
    except ValueError as error:  # PipelineError and the core's InputError: bad input, the message says why
        result = ["failed", str(error), 0]
    except Exception as error:  # noqa: BLE001 - any other failure is reported with its type, not raised
        result = ["failed", f"{type(error).__name__}: {error}", 0]
    with open(spec["result"], "w") as out:
        json.dump(result, out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
