// A QEMU TCG plugin (qemu-user, QEMU 7.2 plugin API version 1) that counts the guest instructions
// executed and writes the running count each time the guest enters a marker function: one line
// "mark COUNT" per entry, then "total COUNT" at exit. Arguments: out=FILE (default stderr) and
// mark=SYMBOL (default mirror_arm_mark; the function must be one `ret`, so that every translation
// block in it starts at its entry), and profile=N: at exit, also the N functions that executed the
// most instructions over the whole run ("function COUNT NAME"; a block counts for the function it
// starts in). Counts are exact and repeat run to run. Built for the host by scripts/bench-arm
// against the header from Debian's qemu source package.
#include <qemu-plugin.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

QEMU_PLUGIN_EXPORT int qemu_plugin_version = QEMU_PLUGIN_VERSION;

static uint64_t count;  // one vCPU: the vision pipeline runs on one thread
static FILE* out;
static const char* markSymbol = "mirror_arm_mark";

// The profile: one counter per function name, looked up once per translated block.
enum { kMaxFunctions = 8192 };
static struct Function {
    const char* name;
    uint64_t count;
} functions[kMaxFunctions];
static int functionCount, profileTop;

static uint64_t* counterOf(const char* name)
{
    for (int i = 0; i < functionCount; ++i)
        if (functions[i].name == name || strcmp(functions[i].name, name) == 0)
            return &functions[i].count;
    if (functionCount == kMaxFunctions)
        return &functions[kMaxFunctions - 1].count;  // the rest, under the last name
    functions[functionCount].name = strdup(name);
    return &functions[functionCount++].count;
}

static int byCount(const void* a, const void* b)
{
    const uint64_t x = ((const struct Function*)a)->count, y = ((const struct Function*)b)->count;
    return x < y ? 1 : x > y ? -1 : 0;
}

static void onMark(unsigned int vcpu, void* udata)
{
    (void)vcpu;
    (void)udata;
    fprintf(out, "mark %llu\n", (unsigned long long)count);
}

static void onTranslate(qemu_plugin_id_t id, struct qemu_plugin_tb* tb)
{
    (void)id;
    qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64, &count,
                                             qemu_plugin_tb_n_insns(tb));
    const char* symbol = qemu_plugin_insn_symbol(qemu_plugin_tb_get_insn(tb, 0));
    if (symbol != NULL && strcmp(symbol, markSymbol) == 0)
        qemu_plugin_register_vcpu_tb_exec_cb(tb, onMark, QEMU_PLUGIN_CB_NO_REGS, NULL);
    if (profileTop > 0)
        qemu_plugin_register_vcpu_tb_exec_inline(tb, QEMU_PLUGIN_INLINE_ADD_U64,
                                                 counterOf(symbol ? symbol : "(no symbol)"),
                                                 qemu_plugin_tb_n_insns(tb));
}

static void onExit(qemu_plugin_id_t id, void* udata)
{
    (void)id;
    (void)udata;
    fprintf(out, "total %llu\n", (unsigned long long)count);
    qsort(functions, (size_t)functionCount, sizeof functions[0], byCount);
    for (int i = 0; i < functionCount && i < profileTop; ++i)
        fprintf(out, "function %llu %s\n", (unsigned long long)functions[i].count,
                functions[i].name);
    fflush(out);
}

QEMU_PLUGIN_EXPORT int qemu_plugin_install(qemu_plugin_id_t id, const qemu_info_t* info, int argc,
                                           char** argv)
{
    (void)info;
    out = stderr;
    for (int i = 0; i < argc; ++i) {
        if (strncmp(argv[i], "out=", 4) == 0 && (out = fopen(argv[i] + 4, "w")) == NULL) {
            fprintf(stderr, "insn_count_plugin: cannot write %s\n", argv[i] + 4);
            return -1;
        }
        if (strncmp(argv[i], "mark=", 5) == 0)
            markSymbol = strdup(argv[i] + 5);
        if (strncmp(argv[i], "profile=", 8) == 0)
            profileTop = atoi(argv[i] + 8);
    }
    qemu_plugin_register_vcpu_tb_trans_cb(id, onTranslate);
    qemu_plugin_register_atexit_cb(id, onExit, NULL);
    return 0;
}
