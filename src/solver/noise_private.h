/* What noise.c and noise_ziggurat.c share: the counter-based generator's hash (random
 * bits that are a pure function of (key, counter)) and the ziggurat's normal numbers.
 * Private to libtiptap. */
#ifndef TIPTAP_SOLVER_NOISE_PRIVATE_H
#define TIPTAP_SOLVER_NOISE_PRIVATE_H

#include <stdint.h>

/* splitmix64's finaliser: a bijection whose output bits each depend on every input bit. */
static inline uint64_t tt_noise_mix64(uint64_t z)
{
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

/* 64 random bits of (key, counter). */
static inline uint64_t tt_noise_bits(uint64_t key, uint64_t ctr)
{
    return tt_noise_mix64(key ^ tt_noise_mix64(ctr * 0x9e3779b97f4a7c15ULL + 0x632be59bd9b4e019ULL));
}

/* A uniform number in (0, 1) from the upper 53 of 64 random bits. */
static inline double tt_noise_unit(uint64_t bits)
{
    return ((double)(bits >> 11) + 0.5) * (1.0 / 9007199254740992.0);
}

/* A standard normal number of (key, index) by the ziggurat (noise_ziggurat.c). */
double tt_noise_ziggurat(uint64_t key, uint64_t index);

#endif
