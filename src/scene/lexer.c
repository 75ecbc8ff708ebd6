/* refray: the tokenizer shared by both scene readers (lexer.h). */
#include "lexer.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int is_space(char c)
{
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

static void step(RfLexer *lx)
{
    if (*lx->p == '\n') {
        lx->line++;
        lx->col = 1;
    } else {
        lx->col++;
    }
    lx->p++;
}

/* Scans the next token into lx->tok. */
static void scan(RfLexer *lx)
{
    int bol = lx->tok.s == NULL; /* the first token of the text */
    for (;;) {
        while (lx->p < lx->end && is_space(*lx->p)) {
            if (*lx->p == '\n')
                bol = 1;
            step(lx);
        }
        if (lx->p < lx->end && *lx->p == '#') {
            while (lx->p < lx->end && *lx->p != '\n')
                step(lx);
            continue;
        }
        break;
    }
    RfToken *t = &lx->tok;
    t->s = lx->p;
    t->line = lx->line;
    t->col = lx->col;
    t->bol = bol;
    if (lx->p >= lx->end) {
        t->kind = RF_TOK_EOF;
        t->len = 0;
        return;
    }
    while (lx->p < lx->end && !is_space(*lx->p) && *lx->p != '#')
        step(lx);
    t->len = (size_t)(lx->p - t->s);
    char c = t->s[0];
    t->kind = (c >= '0' && c <= '9') || c == '+' || c == '-' || c == '.' ? RF_TOK_NUMBER
                                                                         : RF_TOK_WORD;
}

void rf_lex_init_at(RfLexer *lx, const char *name, const char *text, size_t len, int line,
                    char *err, size_t errsz)
{
    memset(lx, 0, sizeof *lx);
    lx->name = name;
    lx->p = text;
    lx->end = text + len;
    lx->line = line;
    lx->col = 1;
    lx->last.kind = RF_TOK_EOF;
    lx->last_end_line = line;
    lx->last_end_col = 1;
    lx->err = err;
    lx->errsz = errsz;
    if (err && errsz)
        err[0] = 0;
    /* a UTF-8 byte order mark at the start of a file is not text (editors write it) */
    if (line == 1 && len >= 3 && memcmp(text, "\xEF\xBB\xBF", 3) == 0)
        lx->p += 3;
    scan(lx);
}

void rf_lex_init(RfLexer *lx, const char *name, const char *text, size_t len, char *err,
                 size_t errsz)
{
    rf_lex_init_at(lx, name, text, len, 1, err, errsz);
}


static const uint32_t pow10_u32[9] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000, 100000000};

/* One run of digits of a decimal (the integer part, or the fraction with frac = 1) into m, sig,
 * digits and scale: m takes every digit, sig counts them from the first nonzero one (a 16th is
 * too many: NULL), scale falls by one per fraction digit. Returns the end of the run. Leading
 * zeros first, then one test per digit (a digit-by-digit test of "m or a nonzero digit" cost the
 * OBJ reader 184 instructions a number). */
static RF_INLINE_ALWAYS const char *decimal_run(const char *s, const char *end, int frac, uint64_t *m, int *sig,
                                                int *digits, int *scale)
{
    const char *start = s;
    uint64_t eight;
    int zeros, n = frac ? rf_lex_digits8(s, end, &eight, &zeros) : -1; /* a fraction: up to 8 digits at once */
    if (n >= 0) {
        int add = *m ? n : n - zeros;
        if (*sig + add > 15)
            return NULL;
        *sig += add;
        *m = *m * (uint64_t)pow10_u32[n] + eight; /* below 10^15 */
        s += n;
        if (n < 8)
            end = s; /* the run ended */
    }
    if (*m == 0)
        while (s < end && *s == '0')
            s++;
    for (; s < end; s++) {
        unsigned d = (unsigned)(unsigned char)*s - '0';
        if (d > 9)
            break;
        if (++*sig > 15)
            return NULL;
        *m = *m * 10 + d;
    }
    *digits += (int)(s - start);
    *scale -= frac ? (int)(s - start) : 0;
    return s;
}

const char *rf_lex_decimal(const char *s, const char *end, double *out)
{
    static const double pow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,
                                     1e8,  1e9,  1e10, 1e11, 1e12, 1e13, 1e14, 1e15,
                                     1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};
    int neg = 0, digits = 0, sig = 0, scale = 0;
    uint64_t m = 0;
    if (s < end && (*s == '+' || *s == '-'))
        neg = *s++ == '-';
    if (!(s = decimal_run(s, end, 0, &m, &sig, &digits, &scale)))
        return NULL;
    if (s < end && *s == '.' && !(s = decimal_run(s + 1, end, 1, &m, &sig, &digits, &scale)))
        return NULL;
    if (digits == 0)
        return NULL;
    if (s < end && (*s == 'e' || *s == 'E')) {
        int eneg = 0, e = 0, edigits = 0;
        s++;
        if (s < end && (*s == '+' || *s == '-'))
            eneg = *s++ == '-';
        for (; s < end && *s >= '0' && *s <= '9'; s++, edigits++)
            if ((e = e * 10 + (*s - '0')) > 400)
                return NULL;
        if (edigits == 0)
            return NULL;
        scale += eneg ? -e : e;
    }
    if (scale < -22 || scale > 22)
        return NULL;
    double v = (double)m; /* exact: m < 10^15 < 2^53 */
    v = scale < 0 ? v / pow10[-scale] : v * pow10[scale];
    *out = neg ? -v : v;
    return s;
}

void rf_lex_advance(RfLexer *lx)
{
    if (lx->tok.kind == RF_TOK_EOF)
        return;
    lx->last = lx->tok;
    lx->last_end_line = lx->line;
    lx->last_end_col = lx->col;
    scan(lx);
}

int rf_lex_is(const RfToken *t, const char *w)
{
    return t->kind == RF_TOK_WORD && strlen(w) == t->len && memcmp(t->s, w, t->len) == 0;
}

int rf_lex_at_statement_start(const RfLexer *lx)
{
    return lx->tok.kind == RF_TOK_EOF || (lx->tok.kind == RF_TOK_WORD && lx->tok.bol);
}

static RfStatus verror(RfLexer *lx, int line, int col, const char *fmt, va_list ap)
{
    if (lx->err && lx->errsz) {
        int n = snprintf(lx->err, lx->errsz, "%s:%d:%d: ", lx->name, line, col);
        if (n >= 0 && (size_t)n < lx->errsz)
            vsnprintf(lx->err + n, lx->errsz - (size_t)n, fmt, ap);
    }
    return RF_ERR_PARSE;
}

RfStatus rf_lex_error(RfLexer *lx, int line, int col, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    RfStatus st = verror(lx, line, col, fmt, ap);
    va_end(ap);
    return st;
}

RfStatus rf_lex_check(RfLexer *lx, int ok, const char *fmt, ...)
{
    if (ok)
        return RF_OK;
    va_list ap;
    va_start(ap, fmt);
    RfStatus st = verror(lx, lx->last.line, lx->last.col, fmt, ap);
    va_end(ap);
    return st;
}

const char *rf_lex_quote(const RfToken *t, char *buf, size_t n)
{
    if (t->kind == RF_TOK_EOF) {
        snprintf(buf, n, "end of file");
        return buf;
    }
    size_t k = 0;
    const size_t shown = 24; /* long tokens are cut: the position already locates them */
    if (k + 1 < n)
        buf[k++] = '\'';
    for (size_t i = 0; i < t->len && i < shown && k + 6 < n; i++) {
        unsigned char c = (unsigned char)t->s[i];
        if (c >= 0x20 && c < 0x7f)
            buf[k++] = (char)c;
        else
            k += (size_t)snprintf(buf + k, n - k, "\\x%02x", c);
    }
    if (t->len > shown && k + 4 < n) {
        memcpy(buf + k, "...", 3);
        k += 3;
    }
    if (k + 1 < n)
        buf[k++] = '\'';
    buf[k < n ? k : n - 1] = 0;
    return buf;
}

/* The token as a NUL-terminated string in buf, or 0 when it is too long to be a number. */
static int token_text(const RfToken *t, char *buf, size_t n)
{
    if (t->len + 1 > n)
        return 0;
    memcpy(buf, t->s, t->len);
    buf[t->len] = 0;
    return 1;
}

/* Common front of rf_lex_number and rf_lex_int: reports a statement that ended early. */
static RfStatus expect_value(RfLexer *lx, const char *what)
{
    if (rf_lex_at_statement_start(lx))
        return rf_lex_error(lx, lx->last_end_line, lx->last_end_col, "missing number: expected %s",
                            what);
    return RF_OK;
}

RfStatus rf_lex_number(RfLexer *lx, const char *what, double *out)
{
    RfStatus st = expect_value(lx, what);
    if (st)
        return st;
    const RfToken t = lx->tok;
    char text[80], q[96];
    char *end = NULL;
    double v = 0.0;
    if (t.len < sizeof text && rf_lex_decimal(t.s, t.s + t.len, &v) == t.s + t.len) {
        rf_lex_advance(lx);
        *out = v;
        return RF_OK;
    }
    if (token_text(&t, text, sizeof text)) {
        errno = 0;
        v = strtod(text, &end);
    }
    if (!end || end == text || *end) /* strtod reads "nan", "inf" too; they fall through */
        return rf_lex_error(lx, t.line, t.col, "expected %s (a number), found %s", what,
                            rf_lex_quote(&t, q, sizeof q));
    if (!isfinite(v))
        return rf_lex_error(lx, t.line, t.col, "%s must be a finite number, found %s", what,
                            rf_lex_quote(&t, q, sizeof q));
    rf_lex_advance(lx);
    *out = v;
    return RF_OK;
}

RfStatus rf_lex_number_ge(RfLexer *lx, const char *what, double lo, double *out)
{
    RfStatus st = rf_lex_number(lx, what, out);
    return st ? st : rf_lex_check(lx, *out >= lo, "%s must be >= %g, found %g", what, lo, *out);
}

RfStatus rf_lex_int(RfLexer *lx, const char *what, long lo, long hi, int *out)
{
    RfStatus st = expect_value(lx, what);
    if (st)
        return st;
    const RfToken t = lx->tok;
    char text[80], q[96];
    char *end = NULL;
    long v = 0;
    if (token_text(&t, text, sizeof text)) {
        errno = 0;
        v = strtol(text, &end, 10);
    }
    if (!end || end == text || *end || errno == ERANGE || v < lo || v > hi)
        return rf_lex_error(lx, t.line, t.col, "%s must be an integer in [%ld, %ld], found %s",
                            what, lo, hi, rf_lex_quote(&t, q, sizeof q));
    rf_lex_advance(lx);
    *out = (int)v;
    return RF_OK;
}

RfStatus rf_lex_vec3(RfLexer *lx, const char *what, RfVec3 *out)
{
    RfStatus st;
    if ((st = rf_lex_number(lx, what, &out->x)) || (st = rf_lex_number(lx, what, &out->y)) ||
        (st = rf_lex_number(lx, what, &out->z)))
        return st;
    return RF_OK;
}

RfStatus rf_lex_rgb(RfLexer *lx, const char *what, RfRgb *out)
{
    RfStatus st;
    if ((st = rf_lex_number_ge(lx, what, 0.0, &out->r)) ||
        (st = rf_lex_number_ge(lx, what, 0.0, &out->g)) ||
        (st = rf_lex_number_ge(lx, what, 0.0, &out->b)))
        return st;
    return RF_OK;
}

RfStatus rf_lex_word(RfLexer *lx, const char *what, RfToken *out)
{
    char q[96];
    if (lx->tok.kind != RF_TOK_WORD)
        return rf_lex_error(lx, lx->tok.line, lx->tok.col, "expected %s, found %s", what,
                            rf_lex_quote(&lx->tok, q, sizeof q));
    *out = lx->tok;
    rf_lex_advance(lx);
    return RF_OK;
}
