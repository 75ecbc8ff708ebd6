#ifndef REFRAY_VERSION_H
#define REFRAY_VERSION_H
#define RF_VERSION "0.1.0"
#endif
