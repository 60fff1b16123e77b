/**
 * @file mathconst.h
 * @brief Mathematical constants shared by every layer (C11 has no M_PI).
 *
 * The literals carry more digits than a double holds, so each constant is the
 * correctly rounded double; 2 pi is exact in binary (a doubling).
 */
#ifndef SPALL_MATHCONST_H
#define SPALL_MATHCONST_H

/** pi */
#define SPALL_PI 3.14159265358979323846
/** 2 pi */
#define SPALL_TWO_PI 6.28318530717958647692

#endif
