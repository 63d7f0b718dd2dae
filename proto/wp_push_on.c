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
