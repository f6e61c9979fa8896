/**
 * @class   pqRockDEMReadOnlyWidget
 * @brief   Properties-panel widget of a RockDEM read-only value (panel_widget="rockdem_read_only").
 *
 * Shows an information-only property (a count, a measurement or a status line) as read-only,
 * selectable text that wraps, whatever its type: ParaView 5.11 has no panel widget for
 * IdType properties, and shows strings as editable boxes that cut long lines off. Counts are
 * shown as integers, real values with six significant digits and the unit the property's
 * documentation names. The text follows the property: it changes whenever the value is
 * pulled from the server (the RockDEM plugin pulls after every command, Apply and render).
 * The label (QLabel) is named "Value", e.g. `.../ProxyPanel/NumberOfElements/Value`, for
 * ParaView's recorded GUI tests.
 */
#ifndef pqRockDEMReadOnlyWidget_h
#define pqRockDEMReadOnlyWidget_h

#include "pqPropertyWidget.h"

class QLabel;

class pqRockDEMReadOnlyWidget : public pqPropertyWidget
{
  Q_OBJECT
  typedef pqPropertyWidget Superclass;

public:
  pqRockDEMReadOnlyWidget(vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent = nullptr);
  ~pqRockDEMReadOnlyWidget() override;

  /// The text shown for a property's current value (unit from its documentation).
  static QString text(vtkSMProperty* property);

private Q_SLOTS:
  void updateText();

private:
  Q_DISABLE_COPY(pqRockDEMReadOnlyWidget)
  QLabel* Label;
};

#endif
