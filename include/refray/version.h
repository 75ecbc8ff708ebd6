#ifndef REFRAY_VERSION_H
#define REFRAY_VERSION_H
#define RF_VERSION "0.2.0"
#endif
