/* wp_push_on.c -- push_on read and checked (wp_push_on.h). */
#include "wp_push_on.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

bool wp_read_push_on(const cJSON *object, const char *path, const wr_fixture *shape, bool **mask,
                     size_t *count, wp_error *error)
{
    *mask = NULL;
    *count = 0;
    const cJSON *value = cJSON_GetObjectItemCaseSensitive(object, "push_on");
    if (!value)
        return true;
    char field[WP_FIELD_MAX];
    wp_path_key(field, path, "push_on");
    size_t loops = shape->shape == WR_SHAPE_OUTLINE && shape->outline ? shape->outline->loop_count : 1;
    if (cJSON_IsString(value) && strcmp(value->valuestring, "all") == 0)
        return true;
    bool *chosen = calloc(loops, sizeof *chosen);
    if (!chosen) {
        wp_error_set(error, WP_INTERNAL, "", "out of memory");
        return false;
    }
    if (cJSON_IsString(value) && strcmp(value->valuestring, "outer") == 0) {
        chosen[0] = true;
    } else if (cJSON_IsArray(value) && cJSON_GetArraySize(value) > 0) {
        size_t i = 0;
        const cJSON *item;
        cJSON_ArrayForEach(item, value)
        {
            char at[WP_FIELD_MAX];
            wp_path_index(at, field, i++);
            double loop = cJSON_IsNumber(item) ? item->valuedouble : NAN;
            if (!(loop >= 0) || loop != floor(loop) || loop >= (double)loops) {
                wp_error_set(error, WP_INVALID_PARAMS, at,
                             "must be a loop of the part's boundary, a whole number from 0 "
                             "(the outer boundary) to %zu", loops - 1);
                free(chosen);
                return false;
            }
            chosen[(size_t)loop] = true;
        }
    } else {
        wp_error_set(error, WP_INVALID_PARAMS, field,
                     "must be \"outer\", \"all\" or a non-empty list of loop numbers");
        free(chosen);
        return false;
    }
    *mask = chosen;
    *count = loops;
    return true;
}

/* One reason: the blocking cone (set and index; index -1: none). */
typedef struct reason {
    wr_set set;
    int index;
    int edges;
} reason;

void wp_write_push_why(wp_buffer *out, const wr_analysis *analysis, wr_set set,
                       const wr_finger *finger)
{
    const wr_fixture *f = wr_analysis_fixture(analysis);
    int edges = wr_push_edge_count(f);
    reason *reasons = calloc((size_t)edges + 1, sizeof *reasons);
    int count = 0;
    for (int e = 0; reasons && e < edges; e++) {
        if (!wr_finger_pushes_on(f, finger, e))
            continue;
        double wrench[3];
        wr_push_wrench(f, e, f->shape == WR_SHAPE_CIRCLE ? 180 : 0.5, wrench);
        wr_answer answer;
        if (wr_classify_margin(analysis, wrench, set, WR_DEFAULT_TOLERANCE, &answer) != WR_OK)
            continue;
        reason r = {answer.blocking >= 0 ? answer.blocking_set : set, answer.blocking, 1};
        int i = 0;
        while (i < count && (reasons[i].set != r.set || reasons[i].index != r.index))
            i++;
        if (i < count)
            reasons[i].edges++;
        else
            reasons[count++] = r;
    }
    /* Most edges first; equal counts in the order first met (insertion). */
    for (int a = 1; a < count; a++)
        for (int b = a; b > 0 && reasons[b].edges > reasons[b - 1].edges; b--) {
            reason swap = reasons[b];
            reasons[b] = reasons[b - 1];
            reasons[b - 1] = swap;
        }
    WP_BUFFER_LITERAL(out, ",\"why_empty\":{\"reasons\":[");
    for (int i = 0; i < count; i++) {
        wp_buffer_puts(out, i ? ",{\"blocking\":" : "{\"blocking\":");
        if (reasons[i].index < 0) {
            WP_BUFFER_LITERAL(out, "null");
        } else {
            char text[WR_CONSTRAINT_TEXT];
            wr_constraint_format(&wr_analysis_cone(analysis, reasons[i].set, reasons[i].index)
                                      ->constraint,
                                 text);
            wp_buffer_string(out, text);
        }
        WP_BUFFER_LITERAL(out, ",\"set\":");
        wp_buffer_string(out, reasons[i].set == WR_SET_GOAL     ? "goal"
                              : reasons[i].set == WR_SET_STRONG ? "strong"
                                                                : "both");
        WP_BUFFER_LITERAL(out, ",\"states\":[");
        if (reasons[i].index >= 0 && reasons[i].set == WR_SET_GOAL) {
            const wr_plan_origins *origins =
                &wr_analysis_plan(analysis)->origins[reasons[i].index];
            for (int j = 0; j < origins->count; j++) {
                char state[WR_STATE_TEXT];
                wr_state_format(origins->states[j], f->fixel_count, state);
                if (j)
                    WP_BUFFER_LITERAL(out, ",");
                wp_buffer_string(out, state);
            }
        }
        WP_BUFFER_LITERAL(out, "],\"edges\":");
        wp_buffer_number(out, reasons[i].edges);
        WP_BUFFER_LITERAL(out, "}");
    }
    WP_BUFFER_LITERAL(out, "]}");
    free(reasons);
}
