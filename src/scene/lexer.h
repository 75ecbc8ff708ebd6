/* refray: the tokenizer shared by the NFF reader and the refray-format reader (internal).
 * A token is a run of characters up to white space or '#'; '#' starts a comment to the end
 * of the line. Tokens that start with a digit, '+', '-' or '.' are numbers, all others words.
 * Every error is written as "name:line:col: message" (1-based line, 1-based byte column). */
#ifndef RF_SCENE_LEXER_H
#define RF_SCENE_LEXER_H

#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "refray/ray.h" /* RF_INLINE_ALWAYS */
#include "refray/rgb.h"
#include "refray/status.h"
#include "refray/vec.h"

typedef enum { RF_TOK_EOF, RF_TOK_WORD, RF_TOK_NUMBER } RfTokKind;

typedef struct {
    RfTokKind kind;
    const char *s;
    size_t len;
    int line, col;
    int bol; /* first token on its line */
} RfToken;

typedef struct {
    const char *name;
    const char *p, *end; /* scan position */
    int line, col;       /* of p */
    RfToken tok;         /* the next token (lookahead) */
    RfToken last;        /* the token consumed last */
    int last_end_line, last_end_col; /* just after the token consumed last */
    char *err;
    size_t errsz;
} RfLexer;

void rf_lex_init(RfLexer *lx, const char *name, const char *text, size_t len, char *err,
                 size_t errsz);
/* The same for a piece of a file that starts at the beginning of line `line`. */
void rf_lex_init_at(RfLexer *lx, const char *name, const char *text, size_t len, int line,
                    char *err, size_t errsz);
/* The decimal number at s (before end): [+-] digits [. digits] [(e|E) [+-] digits], at least one
 * digit before the exponent, up to 15 significant digits and a decimal exponent of at most 22 in
 * magnitude: then the value is one correctly rounded IEEE operation on two exact doubles
 * (Clinger 1990), the same bits as strtod. Returns the end of the number, or NULL for anything
 * else (the caller falls back to strtod). */
const char *rf_lex_decimal(const char *s, const char *end, double *out);
/* The run of ASCII digits at s, up to 8 of them, read as one 8-byte word: returns how many there
 * are (0 to 8; the run may go on after 8), their value in *value and how many of them are leading
 * '0's in *zeros (all of them when the value is 0). -1 when fewer than 8 bytes are left before
 * end (or on a big-endian host): the caller reads those one by one. The OBJ reader's indices and
 * the fractions of its numbers go this way (fewer instructions than digit by digit from about
 * four digits on). */
static RF_INLINE_ALWAYS int rf_lex_digits8(const char *s, const char *end, uint64_t *value, int *zeros)
{
#if defined(__BYTE_ORDER__) && defined(__ORDER_LITTLE_ENDIAN__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__ && \
    defined(__GNUC__)
    if (end - s < 8)
        return -1;
    uint64_t x;
    memcpy(&x, s, sizeof x); /* byte k is s[k]: the first digit is the lowest byte */
    /* per byte b - '0': a digit gives 0..9, whose high bit stays clear in it and in it + 0x76;
     * any other byte sets one of them. Borrows and carries only move up from a byte that is no
     * digit, so every byte below the first such byte is judged right. */
    uint64_t d = x - 0x3030303030303030ULL;
    uint64_t other = (d | (d + 0x7676767676767676ULL)) & 0x8080808080808080ULL;
    int n = other ? __builtin_ctzll(other) >> 3 : 8;
    if (n == 0) {
        *value = 0;
        *zeros = 0;
        return 0;
    }
    d &= n == 8 ? ~0ULL : (1ULL << (8 * n)) - 1; /* the n digits' values, 0..9 a byte */
    uint64_t nonzero = (d + 0x7F7F7F7F7F7F7F7FULL) & 0x8080808080808080ULL;
    *zeros = nonzero ? __builtin_ctzll(nonzero) >> 3 : n;
    /* the n digits as the last n of 8 (leading zeros before them), then pairs, fours, eight:
     * byte k * 10 + byte k + 1, and so on, by multiplications that keep the lanes apart */
    d <<= 8 * (8 - n);
    d = d * 10 + (d >> 8);
    d = (((d & 0x000000FF000000FFULL) * (100 + (1000000ULL << 32))) +
         (((d >> 16) & 0x000000FF000000FFULL) * (1 + (10000ULL << 32)))) >> 32;
    *value = d;
    return n;
#else
    (void)s, (void)end, (void)value, (void)zeros;
    return -1;
#endif
}
/* Consumes the lookahead token (no-op at the end). */
void rf_lex_advance(RfLexer *lx);
/* 1 when the token is the word w. */
int rf_lex_is(const RfToken *t, const char *w);
/* 1 when the lookahead starts a new statement: the end of the text or a word that is the
 * first token on its line. */
int rf_lex_at_statement_start(const RfLexer *lx);

/* Writes "name:line:col: message" and returns RF_ERR_PARSE. */
RfStatus rf_lex_error(RfLexer *lx, int line, int col, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
/* The token, quoted and shortened for a message: 'abc', with non-printable bytes as \xNN. */
const char *rf_lex_quote(const RfToken *t, char *buf, size_t n);
/* When ok is 0: an error at the token consumed last (a value out of range). */
RfStatus rf_lex_check(RfLexer *lx, int ok, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 3, 4)))
#endif
    ;

/* Reads one finite number; `what` names it in messages ("sphere radius"). A statement that
 * ends early reports "missing number" just after its last token; NaN, Inf and overflow are
 * errors at the token. */
RfStatus rf_lex_number(RfLexer *lx, const char *what, double *out);
/* A number >= lo. */
RfStatus rf_lex_number_ge(RfLexer *lx, const char *what, double lo, double *out);
/* An integer in [lo, hi] written without fraction or exponent. */
RfStatus rf_lex_int(RfLexer *lx, const char *what, long lo, long hi, int *out);
/* Three numbers; rf_lex_rgb also requires each >= 0. */
RfStatus rf_lex_vec3(RfLexer *lx, const char *what, RfVec3 *out);
RfStatus rf_lex_rgb(RfLexer *lx, const char *what, RfRgb *out);
/* The next token must be a word (a keyword or a name). */
RfStatus rf_lex_word(RfLexer *lx, const char *what, RfToken *out);

#endif
