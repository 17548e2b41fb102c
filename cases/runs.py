"""The run ledger of a study (cases/<name>/runs.csv, committed): one row per run, so how far
each long run got is known even when the machine that ran it is gone. Used by cases/study.sh.

    runs.py id SCENE MODULUS MODEL [KEY=VALUE ...]   -> "RUN_ID GRID MODEL+CORRECTION" (the --set values win)
    runs.py seconds DURATION                         -> seconds (3h, 170m, 3600s, 3600, 02:50:00)
    runs.py state DIR                                -> new | unfinished | finished | failed
    runs.py recorded LEDGER RUN_ID                   -> the ledger row's state ("" if none)
    runs.py start LEDGER RUN_ID MODULUS MODEL GRID RANKS   (the row says "running")
    runs.py end LEDGER RUN_ID DIR EXIT_CODE SINCE_EPOCH    (the row from DIR/summary.json)
    runs.py table LEDGER [RUN_ID ...]                -> Markdown
    runs.py progress LEDGER OUT                      (each "running" row: step and t of its last
                                                      checkpoint in OUT/<run id>, what a resume continues from)

The ledger and the run ids live in python/voigt_post (ledger.py, run_ids.py); this is their
command line. Standard library only."""
import sys

from voigt_post.ledger import end, progress, recorded, state, table, update
from voigt_post.run_ids import grid_of, run_id, seconds, tagged_model


def main(argv):
    cmd, args = argv[1], argv[2:]
    if cmd == "id":
        grid = grid_of(args[0], args[3:])
        model = tagged_model(args[2], args[3:], args[0])
        print(run_id(args[1], model, grid), grid, model)
    elif cmd == "seconds":
        try:
            print(max(1, round(seconds(args[0]))))  # whole seconds: for the shell's arithmetic
        except ValueError:
            sys.exit("run: --wall-limit '%s' is not a duration (3h, 170m, 3600s, 3600, 02:50:00)" % args[0])
    elif cmd == "state":
        print(state(args[0]))
    elif cmd == "recorded":
        print(recorded(args[0], args[1]))
    elif cmd == "start":
        update(args[0], args[1], dict(zip(["modulus", "model", "grid", "ranks"], args[2:6]), state="running",
                                      to_finish_s=""))
    elif cmd == "end":
        end(args[0], args[1], args[2], int(args[3]), float(args[4]))
    elif cmd == "table":
        print(table(args[0], set(args[1:])))
    elif cmd == "progress":
        for rid in progress(args[0], args[1]):
            print("runs.py: %s: last checkpoint recorded" % rid)
    else:
        sys.exit("runs.py: unknown command '%s'" % cmd)


if __name__ == "__main__":
    main(sys.argv)
