/* example.c -- libwrenchclient in a cell controller's loop: store a fixture,
 * then ask about the pushes the cell is about to make.
 *
 *   wrenchclient-example SOCKET FIXTURE.json
 */
#include "wrenchclient.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* fixture.put through the general call; returns the id in `id`. */
static int put_fixture(wrc_client *client, const char *path, char id[33])
{
    FILE *file = fopen(path, "rb");
    if (!file) {
        perror(path);
        return -1;
    }
    static char fixture[1 << 16];
    size_t length = fread(fixture, 1, sizeof fixture - 1, file);
    fclose(file);
    fixture[length] = 0;
    for (char *c = fixture; *c; c++) /* one line */
        if (*c == '\n' || *c == '\r')
            *c = ' ';
    static char request[(1 << 16) + 128];
    snprintf(request, sizeof request,
             "{\"jsonrpc\":\"2.0\",\"method\":\"fixture.put\",\"params\":{\"fixture\":%s},\"id\":1}",
             fixture);
    char *answer;
    int error = wrc_call(client, request, &answer);
    if (error != WRC_OK) {
        int code;
        const char *field, *reason;
        wrc_server_error(client, &code, &field, &reason);
        fprintf(stderr, "put: %s: %s %s\n", wrc_strerror(error), field, reason);
        free(answer);
        return -1;
    }
    const char *at = strstr(answer, "\"id\":\"");
    if (!at || sscanf(at + 6, "%32[0-9a-f]", id) != 1) {
        free(answer);
        return -1;
    }
    free(answer);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s SOCKET FIXTURE.json\n", argv[0]);
        return 2;
    }
    int error;
    wrc_client *client = wrc_connect(argv[1], 5000, 0, &error);
    if (!client) {
        fprintf(stderr, "%s: %s\n", argv[1], wrc_strerror(error));
        return 3;
    }
    char id[33];
    if (put_fixture(client, argv[2], id) != 0) {
        wrc_close(client);
        return 4;
    }
    printf("fixture %s\n", id);
    const double pushes[3][3] = {{-1, -1, 0}, {-1, -0.2, 0}, {-1, -1, -100}};
    static const char *const verdicts[] = {"inside", "boundary", "outside"};
    for (int i = 0; i < 3; i++) {
        for (int s = 0; s < 2; s++) {
            const char *set = s ? "strong" : "goal";
            wrc_answer answer;
            error = wrc_classify(client, id, pushes[i], set, &answer);
            if (error != WRC_OK) {
                fprintf(stderr, "classify: %s (%s)\n", wrc_strerror(error),
                        wrc_last_error(client));
                wrc_close(client);
                return error == WRC_ESERVER ? 4 : 3;
            }
            printf("(%g, %g, %g) %-6s %-8s margin %+.6f %s\n", pushes[i][0], pushes[i][1],
                   pushes[i][2], set, verdicts[answer.verdict], answer.margin, answer.blocking);
        }
    }
    wrc_close(client);
    return 0;
}
