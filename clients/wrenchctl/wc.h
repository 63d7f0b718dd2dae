/* wc.h -- what wrenchctl's pieces share: the exit statuses, the options,
 * the table of commands and the run of one command.
 *
 * wrenchctl.c holds the table and the dispatcher.  For every command the
 * dispatcher does the common steps in this order, each in one place:
 *
 *   1. its options, wherever they stand (those its row's WC_OPT_* name, and
 *      the global ones), --help, and the count of its arguments;
 *   2. WC_DAEMON: refused with --local (there is no store in process);
 *   3. WC_FIXTURE: its first argument read as a fixture (a file, sent
 *      inline, or a stored fixture's id) into run->fixture; with --friction
 *      (WC_OPT_INTERVAL) a stored one is fetched, and the fixture is sent
 *      inline with its friction replaced by the interval (wc_call.h);
 *   4. the row's request function adds the rest of the params (or refuses
 *      the arguments with an exit status);
 *   5. the request to the daemon, or in process with --local: errors said
 *      and mapped to an exit status by wc_call();
 *   6. with --json (always, for WC_JSON) the result printed as JSON;
 *   7. the row's answer function prints the table (unless --json), draws
 *      any --svg picture and returns the exit status.
 *
 * A row without a method (help) is done by its request function alone. */
#ifndef WC_H
#define WC_H

#include <cjson/cJSON.h>
#include <stdbool.h>
#include <stdio.h>

/* Exit statuses, for scripts: see wrenchctl(1). */
enum {
    EXIT_INSIDE = 0,      /* success; for classify, every wrench inside */
    EXIT_NOT_INSIDE = 1,  /* classify: some wrench not inside */
    EXIT_USAGE = 2,       /* bad command line or input file */
    EXIT_UNREACHABLE = 3, /* no daemon answered */
    EXIT_SERVER = 4       /* the daemon (or the in-process code) answered an error */
};

/* The global options: before or after the command. */
typedef struct wc_options {
    const char *socket_path;
    double timeout_seconds;
    bool json;
    bool local;
    /* Notifications before the answer (design.progress), or NULL. */
    void (*notify)(const char *line, void *context);
    void *notify_context;
} wc_options;

/* A command's flags: what the dispatcher does for it, and the options it
 * takes besides the global ones. */
enum {
    WC_DAEMON = 1 << 0,     /* needs the daemon's store: refused with --local */
    WC_FIXTURE = 1 << 1,    /* the first argument is a FIXTURE (file or id) */
    WC_JSON = 1 << 2,       /* the result is always printed as JSON */
    WC_STDIN = 1 << 3,      /* an argument '-' reads from stdin */
    WC_OPT_SETS = 1 << 8,   /* --sets LIST */
    WC_OPT_METHOD = 1 << 9, /* --method auto|lp */
    WC_OPT_TOLERANCE = 1 << 10, /* --tolerance T */
    WC_OPT_SET = 1 << 11,       /* --set goal|strong|both */
    WC_OPT_FRICTION = 1 << 12,  /* --finger-friction MU */
    WC_OPT_SVG = 1 << 13,       /* --svg FILE */
    WC_OPT_RADIUS = 1 << 14,    /* --finger-radius R */
    WC_OPT_INTERVAL = 1 << 15,  /* --friction LO:HI (or MU): the fixels' friction */
    WC_OPT_SWEEP = 1 << 16,     /* --push SET, --gravity SET, --wrench FX,FY,TAU (repeated),
                                   --range LO:HI, --kinetic-ratio R */
    WC_OPT_DESIGN = 1 << 17,    /* --spacing H, --lattice P,R,NXxNY, --fixels K,
                                   --objective O, --top N, --shard I/N,
                                   --corner-clearance C, --pin-diameter D,
                                   --emit-fixture N FILE,
                                   --symmetric collapse|all */
    WC_OPT_PUSH_ON = 1 << 18,   /* --push-on outer|all|L,L,... */
    WC_OPT_CASE = 1 << 19,      /* --case SPEC (repeated): load cases (wc_force.c) */
    WC_OPT_FORCE = 1 << 20,     /* force: --push X,Y[@DX,DY], --wrench FX,FY,TAU, --range */
    WC_OPT_PUSH_FORCE = 1 << 21, /* push: --force F */
    WC_OPT_GEOMETRIC = 1 << 23, /* --tolerance T[,A] (classify: --fixture-tolerance): the
                                   fixture's geometric tolerance */
    WC_OPT_TILT = 1 << 24,      /* gravity: --in-plane-g A, the pull in a tilted plate's plane */
    WC_OPT_SAMPLES = 1 << 25,   /* push-force: --samples N, exact samples a segment */
    WC_OPT_OVER = 1 << 26,      /* sweep: --over fixels|supports, whose friction is swept */
    WC_OPT_LOCATE = 1 << 22     /* --tolerance T|T1,T2,T3, --feature [NAME=]X,Y (repeated),
                                   --sigma-ratio R */
};

/* One run of one command: its arguments, its options once read, and what
 * the request function keeps for the answer function.  The dispatcher
 * frees every cJSON here after the answer. */
typedef struct wc_run {
    wc_options *o;
    const struct wc_command *command;
    int count;    /* the arguments, options taken out (FIXTURE included) */
    char **items;
    /* WC_OPT_*: NULL or not given when absent */
    cJSON *sets;  /* an array of set names; the request may take it */
    const char *method;
    double tolerance;
    bool tolerance_given;
    const char *set;
    const char *svg;
    double finger_friction;
    bool friction_given;
    double finger_radius;
    bool radius_given;
    double friction_low, friction_high; /* --friction: [low, high], low == high for MU */
    bool friction_interval_given;
    const char *sweep_kind; /* sweep: "push", "gravity" or "wrenches"; NULL when none */
    const char *sweep_set;  /* --push SET or --gravity SET */
    double range[2];        /* --range */
    bool range_given;
    double kinetic_ratio;   /* --kinetic-ratio */
    bool ratio_given;
    bool table_full;        /* --table full: every row, not a summary */
    double spacing;         /* --spacing; 0 when not given */
    int fixels, top;        /* --fixels, --top; 0 when not given */
    const char *objective;  /* --objective */
    int shard[2];           /* --shard I/N */
    bool shard_given;
    bool symmetric_all;     /* --symmetric all: collapse_symmetric false */
    double lattice[2];      /* --lattice PITCH,RADIUS,NXxNY: pitch, peg radius */
    int lattice_extent[2];
    bool lattice_given;
    double corner_clearance; /* --corner-clearance; 0 when not given */
    double pin_diameter;     /* --pin-diameter */
    bool pin_diameter_given;
    int emit_design;         /* --emit-fixture N FILE: design N (from 1); 0: none */
    const char *emit_file;
    cJSON *push_on;          /* --push-on, as sent; NULL: the clients' default */
    int decimals;            /* design-merge: the shards' drawing precision (their
                                summary lines say it); -1: not known */
    /* WC_FIXTURE: the fixture as sent (an object, or an id string) */
    cJSON *fixture;
    /* kept by a request function for its answer (sweep: --wrench, as read) */
    cJSON *wrenches;
    cJSON *bias;
    /* locate: --tolerance (a number or an array), --feature ({"name"?, "at"}
       objects), --sigma-ratio */
    cJSON *locate_tolerance;
    bool geometric_given;         /* WC_OPT_GEOMETRIC */
    double geometric[2];          /* position, angle (degrees) */
    cJSON *features;
    double sigma_ratio;
    bool sigma_ratio_given;
    /* WC_OPT_CASE, WC_OPT_FORCE, WC_OPT_PUSH_FORCE */
    cJSON *cases;           /* the cases, as sent */
    cJSON *force_push;      /* force --push: {"at", "direction"?} */
    cJSON *force_wrench;    /* force --wrench: [fx, fy, tau] */
    double push_force;      /* push --force */
    bool push_force_given;
    /* WC_FIXTURE: --supports FILE|JSON, the fixture's "supports" member
       (sent inline with it); NULL when absent */
    const char *supports;
    double in_plane_g;      /* gravity --in-plane-g A (WC_OPT_TILT) */
    bool in_plane_g_given;
    int samples;            /* push-force --samples N (WC_OPT_SAMPLES); 0: the daemon's default */
    const char *over;       /* sweep --over fixels|supports (WC_OPT_OVER); NULL: not given */
} wc_run;

/* Adds the command's params to `params` (the fixture is already there for
 * WC_FIXTURE).  Returns -1 to go on, or the exit status after saying why
 * not.  For a command without a method it does the whole command and
 * returns its exit status. */
typedef int (*wc_request_fn)(wc_run *run, cJSON *params);

/* Prints `result` as a table unless run->o->json, draws any picture, and
 * returns the exit status.  NULL: nothing to print but JSON, status 0. */
typedef int (*wc_answer_fn)(wc_run *run, const cJSON *result);

typedef struct wc_command {
    const char *name;
    const char *usage;   /* the arguments and options, for the usage line */
    unsigned flags;      /* WC_* */
    int min_args, max_args;
    const char *method;  /* the JSON-RPC method; NULL: no request */
    wc_request_fn request;
    wc_answer_fn answer;
    const char *summary; /* one line, for the list of commands */
    const char *help;    /* what it does, and its options */
} wc_command;

/* The table, ending with a row of NULLs (wrenchctl.c). */
extern const wc_command wc_commands[];

/* `wrenchctl COMMAND --help`: EXIT_INSIDE, or EXIT_USAGE for no such
 * command (said on stderr). */
int wc_command_help(const char *name);

/* `wrenchctl --help`. */
void wc_general_help(void);

#endif
