// A core header that reaches for Qt, for the checker's own test.
#include <QString>
